// Mitsuba's BSDFs and textures to our material and texture blocks; the supported sets are
// the BSDF and texture registries' rows that Mitsuba knows by name.
#include "io/mitsuba/translator.h"
#include <filesystem>
#include "core/bsdf/registry.h"
#include "core/textures/registry.h"

namespace caustica::mitsuba_translation {
namespace fs = std::filesystem;

namespace {
const std::set<std::string>& mitsuba_bsdfs() {
  static const std::set<std::string> names = mitsuba_names(bsdf_plugins());
  return names;
}

// Wrappers of exactly one nested BSDF.
bool takes_one_nested(const std::string& type) {
  return type == "mask" || type == "normalmap" || type == "bumpmap" || type == "coating" || type == "roughcoating";
}

const std::set<std::string>& mitsuba_textures() {
  static const std::set<std::string> names = mitsuba_names(texture_plugins());
  return names;
}
}  // namespace

std::string Translator::material_name(const XmlObject& o, const json* emission) {
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

json Translator::default_emission() {
  XmlProperty one;
  one.number = 1.0;
  return color_json(one, SpectrumUse::Emission);
}

void Translator::count_expansion(const XmlObject& o) {
  if (++expanded_ > kMaxExpanded) {
    throw InputError(o.where + ": the scene expands to more than " + std::to_string(kMaxExpanded) +
                     " BSDFs, textures and shapes (shared references nested too deeply?)");
  }
}

json Translator::bsdf(const XmlObject& o, const std::string& p) {
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
  // Mitsuba's rough plugins default to Beckmann (ours, in JSON scenes, to GGX).
  if ((o.type == "roughconductor" || o.type == "roughdielectric" || o.type == "roughplastic" || o.type == "roughcoating") &&
      !j.contains("distribution")) {
    j["distribution"] = "beckmann";
  }
  json nested = json::array();
  for (const XmlChild& c : o.children) {
    const XmlObject& k = *c.object;
    if (k.tag == "texture") {
      // A bump map's height is its one texture, whatever its name (Mitsuba 3 takes any).
      const std::string name = o.type == "bumpmap" ? "height" : c.name;
      if (name.empty()) throw InputError(c.where + ": a texture inside a BSDF needs a name (the parameter it sets)");
      if (j.contains(name)) throw InputError(c.where + ": \"" + name + "\" is given twice");
      j[name] = texture(k, p + "/" + name);
      note(p + "/" + name, c.where);
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
    } else if (takes_one_nested(o.type) && nested.size() == 1) {
      copy_sources(p + "/bsdf/0", p + "/bsdf");
      j["bsdf"] = nested[0];
    } else if (o.type == "blendbsdf" && nested.size() == 2) {
      j["bsdf"] = nested;
    } else {
      throw InputError(o.where + ": <bsdf type=\"" + o.type + "\"> takes " +
                       (o.type == "twosided"    ? "one or two nested BSDFs"
                        : takes_one_nested(o.type) ? "one nested BSDF"
                        : o.type == "blendbsdf" ? "two nested BSDFs"
                                                : "no nested BSDF"));
    }
  }
  return j;
}

json Translator::texture(const XmlObject& o, const std::string& p) {
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

}  // namespace caustica::mitsuba_translation
