// Mitsuba plugins to our scene document. Each plugin's properties are checked: a property we
// do not know is an error (as in Mitsuba, which refuses unqueried properties), except those
// listed as harmless for that plugin, which are dropped.
#include "io/mitsuba/translate.h"
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include "core/bsdf/registry.h"
#include "core/lights/registry.h"
#include "core/textures/registry.h"
#include "io/mitsuba/shapes.h"
#include "io/mitsuba/spectrum.h"

namespace caustica {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kRoundSegments = 256;
constexpr int kUnlimitedDepth = 1024;

// The plugins of a family that Mitsuba and we both know by one name, from its registry.
template <class Plugin>
std::set<std::string> mitsuba_names(const std::vector<Plugin>& table) {
  std::set<std::string> s;
  for (const Plugin& p : table) {
    if (p.mitsuba) s.insert(p.name);
  }
  return s;
}
const std::set<std::string>& mitsuba_bsdfs() {
  static const std::set<std::string> names = mitsuba_names(bsdf_plugins());
  return names;
}
// Mitsuba's `area` emitter has no row: it sits in a shape and becomes its material's emission.
const std::set<std::string>& mitsuba_emitters() {
  static const std::set<std::string> names = [] {
    std::set<std::string> s = mitsuba_names(light_plugins());
    s.insert("area");
    return s;
  }();
  return names;
}
const std::set<std::string>& mitsuba_textures() {
  static const std::set<std::string> names = mitsuba_names(texture_plugins());
  return names;
}
const std::set<std::string> kShapes = {"obj",  "ply",    "serialized", "rectangle", "cube",
                                       "disk", "sphere", "cylinder",   "shapegroup", "instance"};
const std::set<std::string> kIntegrators = {"path", "volpath", "volpathmis", "direct", "photonmapper",
                                            "sppm", "ppm",  "moment",  "aov"};

std::string list(const std::set<std::string>& s) {
  std::string out;
  for (const std::string& x : s) out += (out.empty() ? "" : ", ") + x;
  return out;
}

json rows(const glm::dmat4& m) {
  json out = json::array();
  for (int r = 0; r < 4; ++r) out.push_back(json::array({m[0][r], m[1][r], m[2][r], m[3][r]}));
  return out;
}

json vec(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

// A plugin's properties, with the ones read marked, so that the rest can be refused.
class Props {
 public:
  explicit Props(const XmlObject& o) : o_(o) {}
  const XmlProperty* get(const std::string& name) {
    used_.insert(name);
    return o_.prop(name);
  }
  void ignore(std::initializer_list<const char*> names) {
    for (const char* n : names) used_.insert(n);
  }
  // The properties nobody read.
  std::vector<const XmlProperty*> unused() const {
    std::vector<const XmlProperty*> out;
    for (const XmlProperty& p : o_.props) {
      if (!used_.count(p.name)) out.push_back(&p);
    }
    return out;
  }

 private:
  const XmlObject& o_;
  std::set<std::string> used_;
};

class Translator {
 public:
  Translator(const XmlScene& scene, const MitsubaOptions& options) : scene_(scene), options_(options) {
    out_.sources = std::make_shared<SourceMap>();
  }

  TranslatedScene run() {
    json& doc = out_.doc;
    doc = {{"render", json::object()}, {"materials", json::object()}, {"objects", json::array()}, {"lights", json::array()}};
    const XmlObject& root = scene_.root();
    note("", root.where);
    note("/objects", root.where);
    bool have_sensor = false, have_integrator = false;
    for (const XmlChild& c : root.children) {
      const XmlObject& o = *c.object;
      if (o.tag == "sensor") {
        if (have_sensor) {
          warn(o.where, "a second <sensor> is ignored (Caustica renders the first)");
          continue;
        }
        have_sensor = true;
        sensor(o);
      } else if (o.tag == "integrator") {
        if (have_integrator) throw InputError(o.where + ": a second <integrator>");
        have_integrator = true;
        integrator(o);
      } else if (o.tag == "shape") {
        if (o.type != "shapegroup") shape(o, glm::dmat4(1.0));  // a group is drawn by its instances
      } else if (o.tag == "emitter") {
        emitter(o);
      } else if (o.tag == "bsdf" || o.tag == "texture") {
        // Materialised where a shape uses it; an unused one is checked all the same.
        if (o.tag == "bsdf") material_name(o, nullptr);
      } else {
        unsupported(o, o.tag, {}, "skipped");
      }
    }
    if (!have_sensor) {
      warn(root.where, "no <sensor>: Mitsuba's default camera (at the origin looking along +z, fov 45 along x, 768x576)");
      doc["camera"] = {{"position", {0, 0, 0}}, {"look_at", {0, 0, 1}}, {"up", {0, 1, 0}}, {"fov", 45}, {"fov_axis", "x"}};
      doc["render"]["width"] = 768;
      doc["render"]["height"] = 576;
      doc["render"]["spp"] = 4;
      doc["render"]["filter"] = {{"type", "gaussian"}, {"stddev", 0.5}};
    }
    if (max_passes_) {  // wins over the sensor's sample count, wherever the sensor is
      doc["render"]["spp"] = integer(*max_passes_);
      note("/render/spp", max_passes_->where);
    }
    if (!have_integrator) {
      doc["integrator"] = {{"type", "path"}, {"rr_depth", 5}};
      doc["render"]["max_depth"] = kUnlimitedDepth;
    }
    return std::move(out_);
  }

 private:
  const XmlScene& scene_;
  const MitsubaOptions& options_;
  TranslatedScene out_;
  std::map<const XmlObject*, std::string> materials_;
  int anonymous_ = 0;
  int expanded_ = 0;
  static constexpr int kMaxExpanded = 100000;

  void note(const std::string& pointer, const std::string& where) { (*out_.sources)[pointer] = where; }
  // The places recorded under pointer `from` (it and its children) recorded under `to` too.
  void copy_sources(const std::string& from, const std::string& to) {
    std::vector<std::pair<std::string, std::string>> copies;
    for (const auto& [k, v] : *out_.sources) {
      if (k.compare(0, from.size(), from) == 0 && (k.size() == from.size() || k[from.size()] == '/')) {
        copies.emplace_back(to + k.substr(from.size()), v);
      }
    }
    for (auto& c : copies) (*out_.sources)[c.first] = c.second;
  }
  void warn(const std::string& where, const std::string& message) { out_.warnings.push_back(where + ": " + message); }

  // An unsupported plugin: an error, or with --ignore-unsupported a warning saying what happens.
  void unsupported(const XmlObject& o, const std::string& family, const std::set<std::string>& supported,
                   const std::string& instead) {
    std::string m = "unsupported " + family + " plugin \"" + o.type + "\"";
    if (o.type.empty()) m = "unsupported element <" + o.tag + ">";
    if (!supported.empty()) m += " (supported: " + list(supported) + ")";
    if (!options_.ignore_unsupported) throw InputError(o.where + ": " + m + "; --ignore-unsupported skips or replaces it");
    warn(o.where, m + ": " + instead);
  }

  void refuse_unused(const XmlObject& o, const Props& props) {
    for (const XmlProperty* p : props.unused()) {
      throw InputError(p->where + ": unknown property \"" + p->name + "\" of <" + o.tag + " type=\"" + o.type + "\">");
    }
  }

  // Unused child objects other than those handled are refused the same way.
  [[noreturn]] void bad_child(const XmlObject& parent, const XmlChild& c) {
    throw InputError(c.where + ": <" + c.object->tag + "> is not expected inside <" + parent.tag + " type=\"" + parent.type + "\">");
  }

  double number(const XmlProperty& p) {
    if (p.kind != XmlProperty::Float && p.kind != XmlProperty::Integer) throw InputError(p.where + ": expected a <float> or <integer>");
    return p.number;
  }
  int64_t integer(const XmlProperty& p) {
    if (p.kind != XmlProperty::Integer && !(p.kind == XmlProperty::Float && p.number == std::floor(p.number))) {
      throw InputError(p.where + ": expected an <integer>");
    }
    if (std::abs(p.number) > 9e15) throw InputError(p.where + ": the integer is too large");
    return int64_t(p.number);
  }
  bool boolean(const XmlProperty& p) {
    if (p.kind != XmlProperty::Boolean) throw InputError(p.where + ": expected a <boolean>");
    return p.boolean;
  }
  std::string string(const XmlProperty& p) {
    if (p.kind != XmlProperty::String) throw InputError(p.where + ": expected a <string>");
    return p.text;
  }
  glm::dvec3 point(const XmlProperty& p) {
    if (p.kind != XmlProperty::Vector) throw InputError(p.where + ": expected a <point> or <vector>");
    return p.vec;
  }
  glm::dmat4 transform(const XmlProperty& p) {
    if (p.kind != XmlProperty::Transform) throw InputError(p.where + ": expected a <transform>");
    return p.matrix;
  }
  Color color(const XmlProperty& p, SpectrumUse use) {
    switch (p.kind) {
      case XmlProperty::Rgb: return Color(p.vec);
      case XmlProperty::Spectrum:
        return p.samples.empty() ? constant_spectrum_to_rgb(p.number, use) : spectrum_to_rgb(p.samples, use);
      case XmlProperty::Blackbody:
        if (use != SpectrumUse::Emission) throw InputError(p.where + ": a blackbody spectrum is for emitters only");
        return float(p.scale) * blackbody_to_rgb(p.number);
      case XmlProperty::Float:
      case XmlProperty::Integer: return Color(float(p.number));
      default: throw InputError(p.where + ": expected a colour (<rgb>, <spectrum> or <float>)");
    }
  }
  json color_json(const XmlProperty& p, SpectrumUse use) {
    const Color c = color(p, use);
    return json::array({c.x, c.y, c.z});
  }

  // A property as a JSON value for the BSDF and texture readers, which check it.
  json value(const XmlProperty& p) {
    switch (p.kind) {
      case XmlProperty::Integer: return int64_t(p.number);
      case XmlProperty::Float: return p.number;
      case XmlProperty::Boolean: return p.boolean;
      case XmlProperty::String: return p.text;
      case XmlProperty::Vector: return vec(p.vec);
      case XmlProperty::Transform: return rows(p.matrix);
      default: {
        const bool unbounded = p.name == "eta" || p.name == "k" || p.name == "int_ior" || p.name == "ext_ior";
        if (p.kind == XmlProperty::Spectrum && p.samples.empty()) return p.number;
        return color_json(p, unbounded ? SpectrumUse::Unbounded : SpectrumUse::Reflectance);
      }
    }
  }

  // A file named in the scene: next to the file naming it, then in the <path> folders.
  std::string resolve(const XmlObject& o, const XmlProperty& p) {
    const std::string name = string(p);
    const fs::path path(name);
    std::error_code ec;
    if (path.is_absolute()) return name;
    // Next to the file naming it, then (for included files) next to the scene, as Mitsuba's
    // file resolver does, then in the <path> folders.
    std::vector<fs::path> tried = {fs::path(o.dir) / path};
    if (o.dir != scene_.root().dir) tried.push_back(fs::path(scene_.root().dir) / path);
    for (const std::string& dir : scene_.search_paths) tried.push_back(fs::path(dir) / path);
    for (const fs::path& t : tried) {
      if (fs::exists(t, ec)) return fs::absolute(t, ec).string();
    }
    std::string all;
    for (const fs::path& t : tried) all += (all.empty() ? "" : ", ") + t.string();
    throw InputError(p.where + ": file not found: tried " + all);
  }

  // ---------------------------------------------------------------- sensor, film, sampler
  void sensor(const XmlObject& o) {
    json& doc = out_.doc;
    if (o.type != "perspective" && o.type != "thinlens") {
      unsupported(o, "sensor", {"perspective", "thinlens"}, "rendered as a pinhole camera");
    }
    Props props(o);
    props.ignore({"near_clip", "far_clip", "shutter_open", "shutter_close"});
    if (o.type != "thinlens") props.ignore({"focus_distance", "aperture_radius"});
    const glm::dmat4 m = props.get("to_world") ? transform(*props.get("to_world")) : glm::dmat4(1.0);
    const glm::dvec3 pos(m[3]), fwd(m * glm::dvec4(0, 0, 1, 0)), up(m * glm::dvec4(0, 1, 0, 0)),
        left(m * glm::dvec4(1, 0, 0, 0));
    if (!(glm::length(fwd) > 0.0) || !(glm::length(up) > 0.0)) throw InputError(props.get("to_world")->where + ": the camera transform is singular");
    json cam = {{"position", vec(pos)}, {"look_at", vec(pos + glm::normalize(fwd))}, {"up", vec(glm::normalize(up))}};
    // Mitsuba's camera space has +x on the image's left; a transform that flips that mirrors the image.
    if (glm::dot(left, glm::cross(up, fwd)) < 0.0) cam["mirror"] = true;
    double fov = 0.0;
    std::string axis = "x";
    if (const XmlProperty* f = props.get("fov")) {
      fov = number(*f);
      if (props.get("focal_length")) throw InputError(f->where + ": give fov or focal_length, not both");
    } else {
      double mm = 50.0;
      if (const XmlProperty* fl = props.get("focal_length")) {
        std::string s = fl->kind == XmlProperty::String ? fl->text : std::to_string(number(*fl));
        if (s.size() > 2 && s.substr(s.size() - 2) == "mm") s.resize(s.size() - 2);
        char* end = nullptr;
        mm = std::strtod(s.c_str(), &end);
        if (end != s.c_str() + s.size() || !(mm > 0.0) || !std::isfinite(mm)) throw InputError(fl->where + ": expected a focal length like \"50mm\"");
      }
      fov = 2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * mm)) * 180.0 / 3.14159265358979323846;
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
    json& render = doc["render"];
    render["width"] = 768;
    render["height"] = 576;
    render["spp"] = 4;
    render["filter"] = {{"type", "gaussian"}, {"stddev", 0.5}};  // Mitsuba's default film's filter
    note("/render", o.where);
    for (const XmlChild& c : o.children) {
      if (c.object->tag == "film") film(*c.object);
      else if (c.object->tag == "sampler") sampler(*c.object);
      else bad_child(o, c);
    }
  }

  void unsupported_property(const XmlProperty& p, const std::string& instead) {
    const std::string m = "unsupported property \"" + p.name + "\"";
    if (!options_.ignore_unsupported) throw InputError(p.where + ": " + m + "; --ignore-unsupported: " + instead);
    warn(p.where, m + ": " + instead);
  }

  void film(const XmlObject& o) {
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

  void rfilter(const XmlObject& o) {
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
    } else {
      // Filters with negative lobes (mitchell, catmullrom, lanczos) cannot be sampled with
      // weight 1; the Gaussian is the nearest positive one.
      warn(o.where, "reconstruction filter \"" + o.type + "\" is rendered as a Gaussian of stddev 0.5 (box, gaussian and tent are supported)");
      render["filter"] = {{"type", "gaussian"}, {"stddev", 0.5}};
      props.ignore({"radius", "lobes", "B", "C", "b", "c"});
    }
    refuse_unused(o, props);
  }

  void sampler(const XmlObject& o) {
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

  // ---------------------------------------------------------------- integrator
  // Mitsuba's max_depth counts path segments (-1: unlimited); ours counts bounces.
  int64_t depth(const XmlProperty* p, int64_t fallback_segments) {
    const int64_t m = p ? integer(*p) : fallback_segments;
    if (m == -1) return kUnlimitedDepth;
    if (m < 2 || m > kUnlimitedDepth + 1) {
      throw InputError((p ? p->where : std::string("integrator")) + ": max_depth " + std::to_string(m) +
                       " is not supported (from 2 to " + std::to_string(kUnlimitedDepth + 1) + ", or -1)");
    }
    return m - 1;
  }

  // Mitsuba 0.6's strictNormals: Caustica always drops light the shading normals would leak.
  void strict_normals(Props& props) {
    if (const XmlProperty* sn = props.get("strict_normals")) {
      if (!boolean(*sn)) warn(sn->where, "strict_normals false: Caustica always uses strict normals");
    }
  }

  const XmlProperty* max_passes_ = nullptr;  // (s)ppm's pass count: the samples per pixel
  void integrator(const XmlObject& o0) {
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
      if (o->type != "path") warn(o->where, "\"" + o->type + "\" without media is the path tracer");
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

  // ---------------------------------------------------------------- BSDFs and textures
  // The material of a BSDF object (made once per object); `emission` adds an area emitter's radiance.
  std::string material_name(const XmlObject& o, const json* emission) {
    const auto it = materials_.find(&o);
    std::string name;
    if (it != materials_.end()) {
      name = it->second;
    } else {
      name = !o.id.empty() ? o.id : "bsdf" + std::to_string(++anonymous_) + " (" + o.type + ")";
      while (out_.doc["materials"].contains(name)) name += "'";
      const std::string p = "/materials/" + name;
      out_.doc["materials"][name] = bsdf(o, p);
      materials_[&o] = name;
    }
    if (!emission) return name;
    std::string lit = name + " + emitter " + std::to_string(++anonymous_);
    json m = out_.doc["materials"][name];
    m["emission"] = *emission;
    out_.doc["materials"][lit] = m;
    // Errors inside the copy point at the BSDF.
    copy_sources("/materials/" + name, "/materials/" + lit);
    return lit;
  }

  // Mitsuba's default radiance, intensity or irradiance: a constant 1 (white in its RGB modes).
  json default_emission() {
    XmlProperty one;
    one.number = 1.0;
    return color_json(one, SpectrumUse::Emission);
  }

  json default_bsdf() { return {{"type", "diffuse"}, {"reflectance", 0.5}}; }

  // Shared references can multiply: each translated BSDF, texture or shape counts.
  void count_expansion(const XmlObject& o) {
    if (++expanded_ > kMaxExpanded) {
      throw InputError(o.where + ": the scene expands to more than " + std::to_string(kMaxExpanded) +
                       " BSDFs, textures and shapes (shared references nested too deeply?)");
    }
  }

  json bsdf(const XmlObject& o, const std::string& p) {
    count_expansion(o);
    note(p, o.where);
    if (!mitsuba_bsdfs().count(o.type)) {
      const XmlObject* inner = nullptr;
      for (const XmlChild& c : o.children) {
        if (c.object->tag == "bsdf" && !inner) inner = c.object;
      }
      if (inner) {
        unsupported(o, "BSDF", mitsuba_bsdfs(), "replaced by its first nested BSDF");
        return bsdf(*inner, p);
      }
      unsupported(o, "BSDF", mitsuba_bsdfs(), "replaced by a grey diffuse BSDF");
      return default_bsdf();
    }
    json j = {{"type", o.type}};
    const bool upgraded = scene_.version.size() && scene_.version[0] < '2';
    // A conductor's exterior index divides eta and k (Mitsuba: eta / ext_eta, k / ext_eta).
    double ext_eta = 1.0;
    if (const XmlProperty* e = o.prop("ext_eta")) {
      if (o.type != "conductor" && o.type != "roughconductor") throw InputError(e->where + ": ext_eta belongs to conductors");
      ext_eta = e->kind == XmlProperty::String ? -1.0 : number(*e);
      if (ext_eta != 1.0 && (!o.prop("eta") || !o.prop("k"))) {
        throw InputError(e->where + ": ext_eta other than 1 needs eta and k given as numbers or colours");
      }
      if (!(ext_eta > 0.0)) throw InputError(e->where + ": ext_eta must be a positive number");
    }
    for (const XmlProperty& prop : o.props) {
      if (prop.name == "sample_visible" || prop.name == "specular_sampling_weight") continue;  // sampling only
      if (prop.name == "ext_eta") continue;
      std::string name = prop.name;
      if (upgraded && o.type == "diffuse" && name == "diffuse_reflectance") name = "reflectance";
      j[name] = value(prop);
      if (ext_eta != 1.0 && (name == "eta" || name == "k")) {
        if (j[name].is_number()) j[name] = j[name].get<double>() / ext_eta;
        else if (j[name].is_array()) for (auto& c : j[name]) c = c.get<double>() / ext_eta;
        else throw InputError(prop.where + ": with ext_eta, " + name + " must be a number or a colour");
      }
      note(p + "/" + name, prop.where);
    }
    json nested = json::array();
    for (const XmlChild& c : o.children) {
      const XmlObject& k = *c.object;
      if (k.tag == "texture") {
        if (c.name.empty()) throw InputError(c.where + ": a texture inside a BSDF needs a name (the parameter it sets)");
        j[c.name] = texture(k, p + "/" + c.name);
        note(p + "/" + c.name, c.where);
      } else if (k.tag == "bsdf") {
        nested.push_back(bsdf(k, p + "/bsdf/" + std::to_string(nested.size())));
      } else {
        bad_child(o, c);
      }
    }
    if (!nested.empty()) {
      if (o.type == "twosided" && nested.size() <= 2) {
        // One BSDF: the pointers recorded under /bsdf/0 name it as /bsdf.
        if (nested.size() == 1) copy_sources(p + "/bsdf/0", p + "/bsdf");
        j["bsdf"] = nested.size() == 1 ? nested[0] : nested;
      } else if (o.type == "mask" && nested.size() == 1) {
        copy_sources(p + "/bsdf/0", p + "/bsdf");
        j["bsdf"] = nested[0];
      } else {
        throw InputError(o.where + ": <bsdf type=\"" + o.type + "\"> takes " +
                         (o.type == "twosided" ? "one or two nested BSDFs" : o.type == "mask" ? "one nested BSDF" : "no nested BSDF"));
      }
    }
    return j;
  }

  json texture(const XmlObject& o, const std::string& p) {
    count_expansion(o);
    note(p, o.where);
    if (!mitsuba_textures().count(o.type)) {
      unsupported(o, "texture", mitsuba_textures(), "replaced by a constant 0.5");
      return 0.5;
    }
    json j = {{"type", o.type}};
    glm::dmat4 to_uv(1.0);
    bool has_to_uv = false;
    double offset[2] = {0, 0}, scale[2] = {1, 1};
    for (const XmlProperty& prop : o.props) {
      const std::string& n = prop.name;
      if (n == "filename" && o.type == "bitmap") {
        j[n] = resolve(o, prop);
      } else if (n == "to_uv") {
        to_uv = transform(prop);
        has_to_uv = true;
      } else if (n == "uoffset" || n == "voffset" || n == "uscale" || n == "vscale") {
        // Mitsuba 0.6: uv * scale + offset.
        (n[1] == 'o' ? offset : scale)[n[0] == 'u' ? 0 : 1] = number(prop);
        has_to_uv = true;
      } else if (n == "color0" || n == "color1") {
        j[n] = color_json(prop, SpectrumUse::Reflectance);
      } else {
        j[n] = value(prop);
      }
      note(p + "/" + n, prop.where);
    }
    if (has_to_uv) {
      glm::dmat4 t(1.0);
      t[3] = glm::dvec4(offset[0], offset[1], 0.0, 1.0);
      glm::dmat4 s(1.0);
      s[0][0] = scale[0], s[1][1] = scale[1];
      const glm::dmat4 m = to_uv * t * s;
      j["to_uv"] = {{m[0][0], m[1][0], m[3][0]}, {m[0][1], m[1][1], m[3][1]}};
    }
    for (const XmlChild& c : o.children) bad_child(o, c);
    return j;
  }

  // ---------------------------------------------------------------- shapes
  void shape(const XmlObject& o, const glm::dmat4& parent) {
    count_expansion(o);
    if (!kShapes.count(o.type)) {
      unsupported(o, "shape", kShapes, "skipped");
      return;
    }
    Props props(o);
    if (o.type == "instance") {
      const XmlObject* group = nullptr;
      for (const XmlChild& c : o.children) {
        if (c.object->tag == "shape" && c.object->type == "shapegroup") group = c.object;
        else bad_child(o, c);
      }
      if (!group) throw InputError(o.where + ": an instance needs a <ref> to a shapegroup");
      const glm::dmat4 m = props.get("to_world") ? transform(*props.get("to_world")) : glm::dmat4(1.0);
      refuse_unused(o, props);
      for (const XmlChild& c : group->children) {
        if (c.object->tag != "shape") bad_child(*group, c);
        shape(*c.object, parent * m);
      }
      return;
    }
    json& objects = out_.doc["objects"];
    const std::string p = "/objects/" + std::to_string(objects.size());
    note(p, o.where);
    const XmlObject* bsdf_obj = nullptr;
    const XmlObject* area = nullptr;
    for (const XmlChild& c : o.children) {
      if (c.object->tag == "bsdf" && !bsdf_obj) bsdf_obj = c.object;
      else if (c.object->tag == "emitter" && !area) area = c.object;
      else if (c.object->tag == "medium") unsupported(*c.object, "medium", {}, "ignored (the shape is rendered without it)");
      else bad_child(o, c);
    }
    json emission;
    if (area) {
      if (area->type != "area") throw InputError(area->where + ": only an \"area\" emitter can be attached to a shape");
      Props ap(*area);
      const XmlProperty* r = ap.get("radiance");
      emission = r ? color_json(*r, SpectrumUse::Emission) : default_emission();
      if (r) note(p + "/material/emission", r->where);
      refuse_unused(*area, ap);
      for (const XmlChild& c : area->children) {
        throw InputError(c.where + ": a textured area emitter is not supported (a constant radiance is)");
      }
    }
    std::string material;
    if (bsdf_obj) {
      material = material_name(*bsdf_obj, area ? &emission : nullptr);
    } else {
      // Mitsuba's default: a diffuse BSDF of reflectance 0.5.
      const std::string name = "default diffuse" + std::string(area ? " + emitter " + std::to_string(++anonymous_) : "");
      json m = default_bsdf();
      if (area) m["emission"] = emission;
      out_.doc["materials"][name] = m;
      note("/materials/" + name, area ? area->where : o.where);
      material = name;
    }
    json obj = {{"name", o.id.empty() ? o.type : o.id}, {"material", material}};
    note(p + "/material", bsdf_obj ? bsdf_obj->where : o.where);
    if (o.type == "obj" && !bsdf_obj && !area) {
      // An OBJ with an .mtl and no BSDF in the scene keeps its own materials (Mitsuba would
      // give it the default diffuse, which faces without a material still get).
      obj.erase("material");
      obj["default_material"] = material;
      note(p + "/default_material", o.where);
    }
    const glm::dmat4 m = parent * (props.get("to_world") ? transform(*props.get("to_world")) : glm::dmat4(1.0));
    if (const XmlProperty* f = props.get("flip_normals")) {
      obj["flip_normal"] = boolean(*f);
      note(p + "/flip_normal", f->where);
    }
    if (o.type == "sphere") {
      glm::dvec3 c(0.0);
      double r = 1.0;
      if (const XmlProperty* cp = props.get("center")) c = point(*cp);
      if (const XmlProperty* rp = props.get("radius")) {
        r = number(*rp);
        note(p + "/radius", rp->where);
      }
      // The transform must keep it a sphere: a uniform scale, rotation and translation.
      const glm::dmat3 l(m);
      const double s = glm::length(l[0]);
      const glm::dmat3 check = glm::transpose(l) * l;
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          if (std::abs(check[a][b] - (a == b ? s * s : 0.0)) > 1e-4 * s * s) {
            throw InputError((o.prop("to_world") ? o.prop("to_world")->where : o.where) +
                             ": a sphere's to_world must be a uniform scale, rotation and translation");
          }
        }
      }
      obj["type"] = "sphere";
      obj["center"] = vec(glm::dvec3(m * glm::dvec4(c, 1.0)));
      obj["radius"] = r * s;
    } else {
      obj["type"] = "mesh";
      glm::dmat4 local(1.0);
      if (o.type == "obj" || o.type == "ply" || o.type == "serialized") {
        const XmlProperty* f = props.get("filename");
        if (!f) throw InputError(o.where + ": missing <string name=\"filename\">");
        obj["file"] = resolve(o, *f);
        note(p + "/file", f->where);
        if (const XmlProperty* si = props.get("shape_index")) {
          if (o.type != "serialized") throw InputError(si->where + ": shape_index applies to serialized shapes only");
          obj["shape_index"] = integer(*si);
          note(p + "/shape_index", si->where);
        }
        if (const XmlProperty* ft = props.get("flip_tex_coords")) {
          // Mitsuba flips OBJ's v by default (as we do) and not PLY's or serialized's.
          if (boolean(*ft) != (o.type == "obj")) unsupported_property(*ft, "ignored");
        }
        props.ignore({"collapse", "max_smooth_angle"});
        if (o.prop("max_smooth_angle")) unsupported_property(*o.prop("max_smooth_angle"), "ignored (the file's normals are used)");
      } else if (o.type == "rectangle") {
        obj.update(rectangle_mesh());
      } else if (o.type == "cube") {
        obj.update(cube_mesh());
      } else if (o.type == "disk") {
        obj.update(disk_mesh(kRoundSegments));
      } else if (o.type == "cylinder") {
        glm::dvec3 p0(0.0), p1(0, 0, 1);
        double radius = 1.0;
        if (const XmlProperty* a = props.get("p0")) p0 = point(*a);
        if (const XmlProperty* b = props.get("p1")) p1 = point(*b);
        if (const XmlProperty* r = props.get("radius")) radius = number(*r);
        const glm::dvec3 axis = p1 - p0;
        const double len = glm::length(axis);
        if (!(len > 0.0) || !(radius > 0.0)) throw InputError(o.where + ": the cylinder has no extent (p0 = p1 or radius <= 0)");
        // Object to world: translate(p0) * frame(axis) * scale(r, r, len).
        const glm::dvec3 w = axis / len;
        const glm::dvec3 u = glm::normalize(std::abs(w.x) > 0.9 ? glm::cross(w, glm::dvec3(0, 1, 0)) : glm::cross(w, glm::dvec3(1, 0, 0)));
        const glm::dvec3 v = glm::cross(w, u);
        local[0] = glm::dvec4(u * radius, 0.0);
        local[1] = glm::dvec4(v * radius, 0.0);
        local[2] = glm::dvec4(w * len, 0.0);
        local[3] = glm::dvec4(p0, 1.0);
        obj.update(cylinder_mesh(kRoundSegments));
      } else {
        throw InputError(o.where + ": a shapegroup is drawn through an <shape type=\"instance\">");
      }
      if (const XmlProperty* fn = props.get("face_normals")) {
        obj["face_normals"] = boolean(*fn);
        note(p + "/face_normals", fn->where);
      }
      const glm::dmat4 full = m * local;
      // Mitsuba's rectangle, disk and cylinder carry their normal through the inverse transpose,
      // which a mirroring transform does not flip, while the triangles' winding does.
      if ((o.type == "rectangle" || o.type == "disk" || o.type == "cylinder") && glm::determinant(glm::dmat3(full)) < 0.0) {
        obj["flip_normal"] = !(obj.contains("flip_normal") && obj["flip_normal"].get<bool>());
      }
      // Mitsuba computes smooth vertex normals for a mesh file without them (unless face_normals).
      if ((o.type == "obj" || o.type == "ply" || o.type == "serialized") &&
          !(obj.contains("face_normals") && obj["face_normals"].get<bool>())) {
        obj["smooth_normals"] = true;
      }
      if (full != glm::dmat4(1.0)) {
        obj["to_world"] = rows(full);
        if (const XmlProperty* t = o.prop("to_world")) note(p + "/to_world", t->where);
      }
    }
    refuse_unused(o, props);
    objects.push_back(obj);
  }

  // ---------------------------------------------------------------- emitters
  void emitter(const XmlObject& o) {
    if (o.type == "area") throw InputError(o.where + ": an area emitter belongs inside a <shape>");
    if (!mitsuba_emitters().count(o.type)) {
      unsupported(o, "emitter", mitsuba_emitters(), "skipped");
      return;
    }
    json& lights = out_.doc["lights"];
    const std::string p = "/lights/" + std::to_string(lights.size());
    note(p, o.where);
    Props props(o);
    json l = {{"type", o.type}};
    const XmlProperty* tw = props.get("to_world");
    const glm::dmat4 m = tw ? transform(*tw) : glm::dmat4(1.0);
    auto emitted = [&](const char* key, const char* ours) {
      const XmlProperty* e = props.get(key);
      l[ours] = e ? color_json(*e, SpectrumUse::Emission)
                  : default_emission();
      if (e) note(p + "/" + ours, e->where);
    };
    auto direction = [&](const glm::dvec3& d, const std::string& where) {
      if (!(glm::length(d) > 0.0)) throw InputError(where + ": the direction is zero");
      return vec(glm::normalize(d));
    };
    if (o.type == "point") {
      const XmlProperty* pos = props.get("position");
      if (pos && tw) throw InputError(pos->where + ": give position or to_world, not both");
      l["position"] = vec(pos ? point(*pos) : glm::dvec3(m[3]));
      emitted("intensity", "intensity");
    } else if (o.type == "spot") {
      l["position"] = vec(glm::dvec3(m[3]));
      l["direction"] = direction(glm::dvec3(m * glm::dvec4(0, 0, 1, 0)), tw ? tw->where : o.where);
      emitted("intensity", "intensity");
      const XmlProperty* cut = props.get("cutoff_angle");
      const XmlProperty* beam = props.get("beam_width");
      const double cutoff = cut ? number(*cut) : 20.0;
      l["cutoff_angle"] = cutoff;
      l["beam_width"] = beam ? number(*beam) : 0.75 * cutoff;
      if (cut) note(p + "/cutoff_angle", cut->where);
      if (beam) note(p + "/beam_width", beam->where);
    } else if (o.type == "directional") {
      const XmlProperty* d = props.get("direction");
      if (d && tw) throw InputError(d->where + ": give direction or to_world, not both");
      l["direction"] = d ? direction(point(*d), d->where) : direction(glm::dvec3(m * glm::dvec4(0, 0, 1, 0)), tw ? tw->where : o.where);
      emitted("irradiance", "irradiance");
    } else if (o.type == "constant") {
      emitted("radiance", "radiance");
    } else {  // envmap
      const XmlProperty* f = props.get("filename");
      if (!f) throw InputError(o.where + ": missing <string name=\"filename\">");
      l["filename"] = resolve(o, *f);
      note(p + "/filename", f->where);
      if (const XmlProperty* s = props.get("scale")) {
        l["scale"] = number(*s);
        note(p + "/scale", s->where);
      }
      if (tw) {
        json r = json::array();
        for (int row = 0; row < 3; ++row) r.push_back(json::array({m[0][row], m[1][row], m[2][row]}));
        l["to_world"] = r;
        note(p + "/to_world", tw->where);
      }
    }
    if (o.type != "spot" && o.type != "point" && o.type != "directional" && o.type != "envmap" && tw) {
      throw InputError(tw->where + ": a " + o.type + " emitter has no to_world");
    }
    refuse_unused(o, props);
    for (const XmlChild& c : o.children) bad_child(o, c);
    lights.push_back(l);
  }
};

}  // namespace

TranslatedScene translate_mitsuba(const XmlScene& scene, const MitsubaOptions& options) {
  return Translator(scene, options).run();
}

TranslatedScene read_mitsuba(const std::string& text, const std::string& file, const std::string& dir,
                             const MitsubaOptions& options) {
  const XmlScene scene = parse_mitsuba_xml(text, file, dir, options.xml);
  return translate_mitsuba(scene, options);
}

}  // namespace caustica
