// Mitsuba's sensor, film, reconstruction filter, sampler and integrator to our camera, render
// and integrator blocks.
#include "io/mitsuba/translator.h"
#include <algorithm>
#include <cmath>
#include <filesystem>

namespace caustica::mitsuba_translation {
namespace fs = std::filesystem;

namespace {
const std::set<std::string> kIntegrators = {"path", "volpath", "volpathmis", "direct", "photonmapper",
                                            "sppm", "ppm",  "moment",  "aov"};
}  // namespace

double Translator::focal_length_fov(const XmlProperty& fl) {
  std::string s = fl.kind == XmlProperty::String ? fl.text : std::to_string(number(fl));
  if (s.size() > 2 && s.substr(s.size() - 2) == "mm") s.resize(s.size() - 2);
  char* end = nullptr;
  const double mm = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !(mm > 0.0) || !std::isfinite(mm)) throw InputError(fl.where + ": expected a focal length like \"50mm\"");
  return 2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * mm)) * 180.0 / 3.14159265358979323846;
}

void Translator::sensor(const XmlObject& o) {
  json& doc = out_.doc;
  if (o.type != "perspective" && o.type != "thinlens" && o.type != "orthographic") {
    unsupported(o, "sensor", {"perspective", "thinlens", "orthographic"}, "rendered as a pinhole camera");
  }
  const bool ortho = o.type == "orthographic";
  Props props(o);
  props.ignore({"far_clip", "shutter_open", "shutter_close"});
  // Mitsuba's orthographic rays start on the near plane; a perspective camera's near clip is ignored.
  const XmlProperty* near_clip = props.get("near_clip");
  const double near = ortho && near_clip ? number(*near_clip) : ortho ? 0.01 : 0.0;
  if (ortho && !(near >= 0.0)) throw InputError(near_clip->where + ": near_clip must not be negative");
  if (o.type != "thinlens") props.ignore({"focus_distance", "aperture_radius"});
  const glm::dmat4 m = props.get("to_world") ? transform(*props.get("to_world")) : glm::dmat4(1.0);
  const glm::dvec3 pos(m[3]), fwd(m * glm::dvec4(0, 0, 1, 0)), up(m * glm::dvec4(0, 1, 0, 0)),
      left(m * glm::dvec4(1, 0, 0, 0));
  if (!(glm::length(fwd) > 0.0) || !(glm::length(up) > 0.0)) throw InputError(props.get("to_world")->where + ": the camera transform is singular");
  // look_at one unit ahead, or further where the position is large: in floats, a point one unit
  // from 1e5 would turn the view by a fraction of a degree (and from 2e7 not move at all).
  const double ahead = std::max(1.0, std::max({std::abs(pos.x), std::abs(pos.y), std::abs(pos.z)}) / 256.0);
  const glm::dvec3 eye = pos + near * fwd;
  json cam = {{"position", vec(eye)}, {"look_at", vec(eye + ahead * glm::normalize(fwd))}, {"up", vec(glm::normalize(up))}};
  // Mitsuba's camera space has +x on the image's left; a transform that flips that mirrors the image.
  if (glm::dot(left, glm::cross(up, fwd)) < 0.0) cam["mirror"] = true;
  if (ortho) {
    // The view is x in [-1, 1] and y in [-1 / aspect, 1 / aspect] in camera space, scaled by
    // to_world: the height follows the film's aspect unless to_world scales y unlike x.
    if (!(glm::length(left) > 0.0)) throw InputError(props.get("to_world")->where + ": the camera transform is singular");
    cam["type"] = "orthographic";
    cam["view_width"] = 2.0 * glm::length(left);
    note("/camera", o.where);
    doc["camera"] = cam;
    render_settings(o);
    const double y_over_x = glm::length(up) / glm::length(left);
    if (std::abs(y_over_x - 1.0) > 1e-6) {
      const double aspect = double(doc["render"]["width"].get<int64_t>()) / double(doc["render"]["height"].get<int64_t>());
      doc["camera"]["view_height"] = 2.0 * glm::length(up) / aspect;
    }
    refuse_unused(o, props);
    return;
  }
  double fov = 0.0;
  std::string axis = "x";
  if (const XmlProperty* f = props.get("fov")) {
    fov = number(*f);
    if (props.get("focal_length")) throw InputError(f->where + ": give fov or focal_length, not both");
  } else {
    XmlProperty fifty;
    fifty.kind = XmlProperty::String;
    fifty.text = "50mm";
    const XmlProperty* fl = props.get("focal_length");
    fov = focal_length_fov(fl ? *fl : fifty);
    axis = "diagonal";
  }
  // With a focal length Mitsuba 3 measures the diagonal, whatever fov_axis says.
  if (const XmlProperty* a = props.get("fov_axis")) {
    if (!o.prop("focal_length") || o.prop("fov")) axis = string(*a);
  }
  cam["fov"] = fov;
  cam["fov_axis"] = axis;
  if (o.type == "thinlens") {
    const XmlProperty* a = props.get("aperture_radius");
    const XmlProperty* f = props.get("focus_distance");
    if (!a || !f) throw InputError(o.where + ": a thinlens sensor needs aperture_radius and focus_distance");
    cam["aperture_radius"] = number(*a);
    cam["focus_distance"] = number(*f);
    note("/camera/aperture_radius", a->where);
    note("/camera/focus_distance", f->where);
  }
  note("/camera", o.where);
  if (const XmlProperty* f = o.prop("fov")) note("/camera/fov", f->where);
  if (const XmlProperty* a = o.prop("fov_axis")) note("/camera/fov_axis", a->where);
  doc["camera"] = cam;
  for (const char* key : {"principal_point_offset_x", "principal_point_offset_y"}) {
    if (const XmlProperty* pp = props.get(key)) {
      if (number(*pp) != 0.0) unsupported_property(*pp, "ignored");
    }
  }
  refuse_unused(o, props);
  render_settings(o);
}

void Translator::render_settings(const XmlObject& o) {
  json& render = out_.doc["render"];
  render["width"] = 768;
  render["height"] = 576;
  render["spp"] = 4;
  render["filter"] = {{"type", "gaussian"}, {"stddev", 0.5}};  // Mitsuba's default film's filter
  note("/render", o.where);
  for (const XmlChild& c : o.children) {
    if (c.object->tag == "film") film(*c.object);
    else if (c.object->tag == "sampler") sampler(*c.object);
    else if (c.object->tag == "medium") camera_medium_ = medium(*c.object);
    else bad_child(o, c);
  }
}

void Translator::unsupported_property(const XmlProperty& p, const std::string& instead) {
  const std::string m = "unsupported property \"" + p.name + "\"";
  if (!options_.ignore_unsupported) throw InputError(p.where + ": " + m + "; --ignore-unsupported: " + instead);
  warn(p.where, m + ": " + instead);
}

void Translator::film(const XmlObject& o) {
  if (o.type != "hdrfilm" && o.type != "ldrfilm" && o.type != "specfilm") {
    unsupported(o, "film", {"hdrfilm", "ldrfilm", "specfilm"}, "read as hdrfilm");
  }
  Props props(o);
  props.ignore({"file_format", "pixel_format", "component_format", "banner", "high_quality_edges", "sample_border",
                "compensate", "attach_log", "gamma", "exposure", "tonemap_method", "key", "burn", "dithering"});
  json& render = out_.doc["render"];
  auto size = [&](const char* key, int64_t fallback) {
    const XmlProperty* p = props.get(key);
    const int64_t v = p ? integer(*p) : fallback;
    if (p && (v < 1 || v > 16384)) throw InputError(p->where + ": must be from 1 to 16384");
    return v;
  };
  const int64_t w = size("width", 768), h = size("height", 576);
  render["width"] = w;
  render["height"] = h;
  const XmlProperty *cx = props.get("crop_offset_x"), *cy = props.get("crop_offset_y"), *cw = props.get("crop_width"),
                    *ch = props.get("crop_height");
  if (cx || cy || cw || ch) {
    const int64_t x = cx ? integer(*cx) : 0, y = cy ? integer(*cy) : 0;
    const int64_t cwv = cw ? integer(*cw) : w - x, chv = ch ? integer(*ch) : h - y;
    render["crop"] = {x, y, cwv, chv};
    note("/render/crop", (cw ? cw : cx ? cx : cy ? cy : ch)->where);
  }
  refuse_unused(o, props);
  // Without an rfilter, Mitsuba's default Gaussian (set with the sensor) stays.
  for (const XmlChild& c : o.children) {
    if (c.object->tag != "rfilter") bad_child(o, c);
    rfilter(*c.object);
  }
}

void Translator::rfilter(const XmlObject& o) {
  json& render = out_.doc["render"];
  Props props(o);
  note("/render/filter", o.where);
  if (o.type == "box") {
    // Mitsuba's box may name its radius (default 0.5, one pixel across).
    if (const XmlProperty* r = props.get("radius")) {
      if (number(*r) != 0.5) warn(r->where, "a box filter of radius other than 0.5 is rendered with radius 0.5");
    }
    render["filter"] = "box";
  } else if (o.type == "gaussian") {
    const XmlProperty* s = props.get("stddev");
    render["filter"] = {{"type", "gaussian"}, {"stddev", s ? number(*s) : 0.5}};
    if (s) note("/render/filter/stddev", s->where);
  } else if (o.type == "tent") {
    const XmlProperty* r = props.get("radius");
    render["filter"] = {{"type", "tent"}, {"radius", r ? number(*r) : 1.0}};
    if (r) note("/render/filter/radius", r->where);
  } else if (o.type == "mitchell") {
    json f = {{"type", "mitchell"}};
    for (const char* key : {"B", "C"}) {
      if (const XmlProperty* v = props.get(key)) {
        f[key] = number(*v);
        note(std::string("/render/filter/") + key, v->where);
      }
    }
    render["filter"] = f;
  } else if (o.type == "catmullrom") {
    render["filter"] = {{"type", "catmullrom"}};
  } else if (o.type == "lanczos") {
    json f = {{"type", "lanczos"}};
    if (const XmlProperty* v = props.get("lobes")) {
      f["lobes"] = integer(*v);
      note("/render/filter/lobes", v->where);
    }
    render["filter"] = f;
  } else {
    throw InputError(o.where + ": unknown reconstruction filter \"" + o.type +
                     "\" (known: box, gaussian, tent, mitchell, catmullrom, lanczos)");
  }
  refuse_unused(o, props);
}

void Translator::sampler(const XmlObject& o) {
  Props props(o);
  props.ignore({"scramble_seed", "jitter", "dimension", "strategy"});
  json& render = out_.doc["render"];
  if (const XmlProperty* p = props.get("sample_count")) {
    const int64_t n = integer(*p);
    if (n < 1 || n > (1 << 24)) throw InputError(p->where + ": sample_count must be from 1 to 16777216");
    render["spp"] = n;
  }
  if (const XmlProperty* p = props.get("seed")) {
    const int64_t s = integer(*p);
    if (s < 0) throw InputError(p->where + ": the seed must not be negative");
    render["seed"] = s;
  }
  refuse_unused(o, props);
}

int64_t Translator::depth(const XmlProperty* p, int64_t fallback_segments) {
  const int64_t m = p ? integer(*p) : fallback_segments;
  if (m == -1) return kUnlimitedDepth;
  if (m < 1 || m > kUnlimitedDepth + 1) {
    throw InputError((p ? p->where : std::string("integrator")) + ": max_depth " + std::to_string(m) +
                     " is not supported (from 1 to " + std::to_string(kUnlimitedDepth + 1) + ", or -1)");
  }
  return m - 1;
}

void Translator::strict_normals(Props& props) {
  if (const XmlProperty* sn = props.get("strict_normals")) {
    if (!boolean(*sn)) warn(sn->where, "strict_normals false: Caustica always uses strict normals");
  }
}

void Translator::integrator(const XmlObject& o0) {
  if (!options_.integrator_replaced_by.empty() && !kIntegrators.count(o0.type)) {
    // One we do not have: not interpreted (its settings mean nothing to ours), but its path
    // length is the scene's, and stays. (One we have is read as usual: --integrator photon on a
    // photonmapper scene keeps its photon counts.)
    std::string kept;
    const XmlProperty* p = o0.prop("max_depth");
    if (p && p->kind == XmlProperty::Integer) {
      try {
        out_.doc["render"]["max_depth"] = depth(p, -1);
        note("/render/max_depth", p->where);
        kept = "; its max_depth " + std::to_string(integer(*p)) + " is kept";
      } catch (const InputError&) {
      }
    }
    warn(o0.where, "the scene's integrator \"" + o0.type + "\" is replaced by " + options_.integrator_replaced_by + kept);
    return;
  }
  const XmlObject* o = &o0;
  while (o->type == "moment" || o->type == "aov") {
    const XmlObject* inner = nullptr;
    for (const XmlChild& c : o->children) {
      if (c.object->tag == "integrator" && !inner) inner = c.object;
    }
    warn(o->where, "the \"" + o->type + "\" wrapper is unwrapped: Caustica renders " +
                       (inner ? "its integrator" : "the default path tracer"));
    if (!inner) {
      out_.doc["integrator"] = {{"type", "path"}, {"rr_depth", 5}};
      out_.doc["render"]["max_depth"] = kUnlimitedDepth;
      return;
    }
    o = inner;
  }
  json& doc = out_.doc;
  Props props(*o);
  note("/integrator", o->where);
  json integ;
  if (o->type == "path" || o->type == "volpath" || o->type == "volpathmis") {
    // (volpath and volpathmis: our path tracer renders media.)
    integ = {{"type", "path"}};
    doc["render"]["max_depth"] = depth(props.get("max_depth"), -1);
    const XmlProperty* rr = props.get("rr_depth");
    integ["rr_depth"] = rr ? integer(*rr) : 5;
    if (rr) note("/integrator/rr_depth", rr->where);
    strict_normals(props);
  } else if (o->type == "direct") {
    integ = {{"type", "path"}};
    doc["render"]["max_depth"] = 1;
    props.ignore({"emitter_samples", "bsdf_samples", "shading_samples"});
    strict_normals(props);
    warn(o->where, "\"direct\" is rendered as the path tracer with one bounce (emitter and BSDF sampling by MIS)");
  } else if (o->type == "photonmapper" || o->type == "sppm" || o->type == "ppm") {
    // photonmapper: Jensen's two passes; ppm: the same, progressive; sppm: our sppm.
    integ = {{"type", o->type == "sppm" ? "sppm" : "photon"}};
    // photon is progressive by default: photonmapper asks for one pair of maps.
    if (o->type != "sppm") integ["progressive"] = o->type == "ppm";
    doc["render"]["max_depth"] = depth(props.get("max_depth"), -1);
    auto copy = [&](const char* from, const char* to, bool is_integer) {
      if (const XmlProperty* p = props.get(from)) {
        if (is_integer) {
          integ[to] = integer(*p);
        } else {
          integ[to] = number(*p);
        }
        note(std::string("/integrator/") + to, p->where);
      }
    };
    copy("photon_count", "photons", true);
    copy("alpha", "alpha", false);
    if (o->type == "sppm") {
      // Mitsuba's initial radius 0 means "choose one", as ours does.
      const XmlProperty* r = props.get("initial_radius");
      if (r && number(*r) > 0) copy("initial_radius", "radius", false);
    } else {
      copy("global_photons", "photons", true);
      copy("caustic_photons", "caustic_photons", true);
      copy("lookup_size", "global_k", true);
      copy("global_lookup_size", "global_k", true);
      copy("caustic_lookup_size", "caustic_k", true);
      copy("direct_samples", "direct_samples", true);
    }
    // A pass count is the number of samples per pixel: each pass is one sample.
    if (const XmlProperty* p = props.get("max_passes"); p && integer(*p) > 0) max_passes_ = p;
    std::string ignored;
    for (const XmlProperty* p : props.unused()) {
      if (p->name != "hide_emitters") ignored += (ignored.empty() ? "" : ", ") + p->name;
    }
    props.ignore({"volume_photons", "glossy_samples", "rr_depth", "granularity", "global_lookup_radius",
                  "caustic_lookup_radius", "volume_lookup_size", "gather_locally", "auto_cancel_gathering",
                  "max_specular_depth", "initial_radius", "alpha", "max_passes", "photon_count", "global_photons",
                  "caustic_photons", "lookup_size", "global_lookup_size", "caustic_lookup_size", "direct_samples"});
    if (o->type == "ppm") {
      warn(o->where, "\"ppm\" is rendered by Caustica's progressive photon mapper (final gathering and a caustic map, "
                     "Knaus-Zwicker radii)");
    }
    if (!ignored.empty()) warn(o->where, "settings without a counterpart here are ignored: " + ignored);
  } else {
    if (!options_.ignore_unsupported) {
      throw InputError(o->where + ": unsupported integrator plugin \"" + o->type + "\" (supported: " + list(kIntegrators) +
                       "); render the scene with --integrator path or --integrator photon instead");
    }
    unsupported(*o, "integrator", kIntegrators, "the path tracer renders instead");
    integ = {{"type", "path"}, {"rr_depth", 5}};
    doc["render"]["max_depth"] = kUnlimitedDepth;
    doc["integrator"] = integ;
    return;
  }
  if (const XmlProperty* p = o->prop("max_depth")) note("/render/max_depth", p->where);
  if (const XmlProperty* h = props.get("hide_emitters")) {
    if (boolean(*h)) {
      integ["hide_emitters"] = true;
      note("/integrator/hide_emitters", h->where);
    }
  }
  refuse_unused(*o, props);
  doc["integrator"] = integ;
}

}  // namespace caustica::mitsuba_translation
