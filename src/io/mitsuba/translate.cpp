// Mitsuba plugins to our scene document. Each plugin's properties are checked: a property we
// do not know is an error (as in Mitsuba, which refuses unqueried properties), except those
// listed as harmless for that plugin, which are dropped. This file: the document and property
// values; each family is translated in its translate_*.cpp.
#include "io/mitsuba/translator.h"
#include <cmath>
#include <filesystem>

namespace caustica::mitsuba_translation {
namespace fs = std::filesystem;

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

TranslatedScene Translator::run() {
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
    } else if (o.tag == "medium") {
      // Declared for shapes and the sensor to refer to: translated there (one nothing refers
      // to would make a scene of media for nothing).
    } else if ((o.tag == "sampler" || o.tag == "film" || o.tag == "rfilter") && !o.id.empty()) {
      // Declared with an id for a sensor to refer to: read there.
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
  if (!camera_medium_.empty() && doc.contains("camera")) doc["camera"]["medium"] = camera_medium_;
  if (!have_integrator) {
    doc["integrator"] = {{"type", "path"}, {"rr_depth", 5}};
    doc["render"]["max_depth"] = kUnlimitedDepth;
  }
  return std::move(out_);
}

void Translator::copy_sources(const std::string& from, const std::string& to) {
  std::vector<std::pair<std::string, std::string>> copies;
  for (const auto& [k, v] : *out_.sources) {
    if (k.compare(0, from.size(), from) == 0 && (k.size() == from.size() || k[from.size()] == '/')) {
      copies.emplace_back(to + k.substr(from.size()), v);
    }
  }
  for (auto& c : copies) (*out_.sources)[c.first] = c.second;
}

void Translator::unsupported(const XmlObject& o, const std::string& family, const std::set<std::string>& supported, const std::string& instead) {
  std::string m = "unsupported " + family + " plugin \"" + o.type + "\"";
  if (o.type.empty()) m = "unsupported element <" + o.tag + ">";
  if (!supported.empty()) m += " (supported: " + list(supported) + ")";
  if (!options_.ignore_unsupported) throw InputError(o.where + ": " + m + "; --ignore-unsupported skips or replaces it");
  warn(o.where, m + ": " + instead);
}

void Translator::refuse_unused(const XmlObject& o, const Props& props) {
  for (const XmlProperty* p : props.unused()) {
    throw InputError(p->where + ": unknown property \"" + p->name + "\" of <" + o.tag + " type=\"" + o.type + "\">");
  }
}

void Translator::bad_child(const XmlObject& parent, const XmlChild& c) {
  throw InputError(c.where + ": <" + c.object->tag + "> is not expected inside <" + parent.tag + " type=\"" + parent.type + "\">");
}

double Translator::number(const XmlProperty& p) {
  if (p.kind != XmlProperty::Float && p.kind != XmlProperty::Integer) throw InputError(p.where + ": expected a <float> or <integer>");
  return p.number;
}

int64_t Translator::integer(const XmlProperty& p) {
  if (p.kind != XmlProperty::Integer && !(p.kind == XmlProperty::Float && p.number == std::floor(p.number))) {
    throw InputError(p.where + ": expected an <integer>");
  }
  if (std::abs(p.number) > 9e15) throw InputError(p.where + ": the integer is too large");
  return int64_t(p.number);
}

bool Translator::boolean(const XmlProperty& p) {
  if (p.kind != XmlProperty::Boolean) throw InputError(p.where + ": expected a <boolean>");
  return p.boolean;
}

std::string Translator::string(const XmlProperty& p) {
  if (p.kind != XmlProperty::String) throw InputError(p.where + ": expected a <string>");
  return p.text;
}

glm::dvec3 Translator::point(const XmlProperty& p) {
  if (p.kind != XmlProperty::Vector) throw InputError(p.where + ": expected a <point> or <vector>");
  return p.vec;
}

glm::dmat4 Translator::transform(const XmlProperty& p) {
  if (p.kind != XmlProperty::Transform) throw InputError(p.where + ": expected a <transform>");
  return p.matrix;
}

Color Translator::color(const XmlProperty& p, SpectrumUse use) {
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

json Translator::color_json(const XmlProperty& p, SpectrumUse use) {
  const Color c = color(p, use);
  return json::array({c.x, c.y, c.z});
}

json Translator::value(const XmlProperty& p) {
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

std::string Translator::resolve(const XmlObject& o, const XmlProperty& p) {
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

}  // namespace caustica::mitsuba_translation

namespace caustica {

TranslatedScene translate_mitsuba(const XmlScene& scene, const MitsubaOptions& options) {
  return mitsuba_translation::Translator(scene, options).run();
}

TranslatedScene read_mitsuba(const std::string& text, const std::string& file, const std::string& dir,
                             const MitsubaOptions& options) {
  const XmlScene scene = parse_mitsuba_xml(text, file, dir, options.xml);
  return translate_mitsuba(scene, options);
}

}  // namespace caustica
