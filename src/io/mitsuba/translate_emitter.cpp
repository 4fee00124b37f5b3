// Mitsuba's emitters to our lights; the supported set is the light registry's rows that
// Mitsuba knows by name, and `area` (an emitter inside a shape).
#include "io/mitsuba/translator.h"
#include <filesystem>
#include "core/lights/registry.h"

namespace caustica::mitsuba_translation {
namespace fs = std::filesystem;

namespace {
// Mitsuba's `area` emitter has no row: it sits in a shape and becomes its material's emission.
const std::set<std::string>& mitsuba_emitters() {
  static const std::set<std::string> names = [] {
    std::set<std::string> s = mitsuba_names(light_plugins());
    s.insert("area");
    return s;
  }();
  return names;
}
}  // namespace

void Translator::emitter(const XmlObject& o) {
  if (o.type == "area") {
    // Declared with an id, it is drawn by the shapes that refer to it (<ref id="..."/>).
    if (!o.id.empty()) return;
    throw InputError(o.where + ": an area emitter belongs inside a <shape> (or, with an id, is referred to from one)");
  }
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
  if (o.type == "spot" || o.type == "projector") {
    l["position"] = vec(glm::dvec3(m[3]));
    l["direction"] = direction(glm::dvec3(m * glm::dvec4(0, 0, 1, 0)), tw ? tw->where : o.where);
    // The frame's up orients a texture or an image; a mirroring to_world is not kept.
    l["up"] = direction(glm::dvec3(m * glm::dvec4(0, 1, 0, 0)), tw ? tw->where : o.where);
  }
  if (o.type == "point") {
    const XmlProperty* pos = props.get("position");
    if (pos && tw) throw InputError(pos->where + ": give position or to_world, not both");
    l["position"] = vec(pos ? point(*pos) : glm::dvec3(m[3]));
    emitted("intensity", "intensity");
  } else if (o.type == "projector") {
    if (const XmlProperty* e = props.get("irradiance")) {
      l["irradiance"] = color_json(*e, SpectrumUse::Emission);
      note(p + "/irradiance", e->where);
    }
    for (const char* key : {"scale", "fov"}) {
      if (const XmlProperty* v = props.get(key)) {
        l[key] = number(*v);
        note(p + "/" + key, v->where);
      }
    }
    // Without fov, Mitsuba measures the default (or focal_length's) angle diagonally.
    if (const XmlProperty* a = props.get("fov_axis")) {
      if (props.get("fov")) l["fov_axis"] = string(*a);
    }
    if (const XmlProperty* fl = props.get("focal_length")) {
      if (props.get("fov")) throw InputError(fl->where + ": give fov or focal_length, not both");
      l["fov"] = focal_length_fov(*fl);
      l["fov_axis"] = "diagonal";
    }
  } else if (o.type == "spot") {
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
  } else {
    // A light registered for Mitsuba needs its properties mapped here first.
    if (o.type != "envmap") throw InputError(o.where + ": emitter \"" + o.type + "\" has no Mitsuba translation yet");
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
  if (o.type != "spot" && o.type != "projector" && o.type != "point" && o.type != "directional" && o.type != "envmap" && tw) {
    throw InputError(tw->where + ": a " + o.type + " emitter has no to_world");
  }
  if (const XmlProperty* w = props.get("sampling_weight")) {
    l["sampling_weight"] = number(*w);
    note(p + "/sampling_weight", w->where);
  }
  refuse_unused(o, props);
  // The spot's texture and the projector's image.
  const std::string texture_key = o.type == "spot" ? "texture" : o.type == "projector" ? "irradiance" : "";
  for (const XmlChild& c : o.children) {
    if (texture_key.empty() || c.object->tag != "texture" || c.name != texture_key) bad_child(o, c);
    l[texture_key] = texture(*c.object, p + "/" + texture_key);
    note(p + "/" + texture_key, c.where);
  }
  lights.push_back(l);
}

}  // namespace caustica::mitsuba_translation
