// What the Mitsuba translator's files share: the Translator, whose member functions are defined
// per family (translate.cpp: the document and property values; translate_render.cpp: sensor,
// film, sampler, integrator; translate_bsdf.cpp: BSDFs and textures; translate_shape.cpp;
// translate_emitter.cpp), and its helpers. Internal to src/io/mitsuba.
#pragma once
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include "io/mitsuba/spectrum.h"
#include "io/mitsuba/translate.h"
#include "io/mitsuba/xml_tree.h"

namespace caustica::mitsuba_translation {
using nlohmann::json;

constexpr int kRoundSegments = 256;
constexpr int kUnlimitedDepth = 1024;

// The plugins of a family that Mitsuba and we both know by one name, from its registry.
template <class Plugin>
inline std::set<std::string> mitsuba_names(const std::vector<Plugin>& table) {
  std::set<std::string> s;
  for (const Plugin& p : table) {
    if (p.mitsuba) s.insert(p.name);
  }
  return s;
}

// "a, b, c".
std::string list(const std::set<std::string>& s);
// A matrix as 4 rows (our JSON's to_world).
json rows(const glm::dmat4& m);
json vec(const glm::dvec3& v);

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

  TranslatedScene run();

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
  void copy_sources(const std::string& from, const std::string& to);
  void warn(const std::string& where, const std::string& message) { out_.warnings.push_back(where + ": " + message); }

  // An unsupported plugin: an error, or with --ignore-unsupported a warning saying what happens.
  void unsupported(const XmlObject& o, const std::string& family, const std::set<std::string>& supported, const std::string& instead);

  void refuse_unused(const XmlObject& o, const Props& props);

  // Unused child objects other than those handled are refused the same way.
  [[noreturn]] void bad_child(const XmlObject& parent, const XmlChild& c);

  double number(const XmlProperty& p);
  int64_t integer(const XmlProperty& p);
  bool boolean(const XmlProperty& p);
  std::string string(const XmlProperty& p);
  glm::dvec3 point(const XmlProperty& p);
  glm::dmat4 transform(const XmlProperty& p);
  Color color(const XmlProperty& p, SpectrumUse use);
  json color_json(const XmlProperty& p, SpectrumUse use);

  // A property as a JSON value for the BSDF and texture readers, which check it.
  json value(const XmlProperty& p);

  // A file named in the scene: next to the file naming it, then in the <path> folders.
  std::string resolve(const XmlObject& o, const XmlProperty& p);

  // ---------------------------------------------------------------- sensor, film, sampler
  void sensor(const XmlObject& o);

  void unsupported_property(const XmlProperty& p, const std::string& instead);

  void film(const XmlObject& o);

  void rfilter(const XmlObject& o);
  // A 35 mm film's diagonal field of view in degrees for a focal length like "50mm".
  double focal_length_fov(const XmlProperty& focal_length);
  // The sensor's film and sampler (Mitsuba's defaults where absent).
  void render_settings(const XmlObject& sensor);

  void sampler(const XmlObject& o);

  // ---------------------------------------------------------------- integrator
  // Mitsuba's max_depth counts path segments (-1: unlimited); ours counts bounces.
  int64_t depth(const XmlProperty* p, int64_t fallback_segments);

  // Mitsuba 0.6's strictNormals: Caustica always drops light the shading normals would leak.
  void strict_normals(Props& props);

  const XmlProperty* max_passes_ = nullptr;  // (s)ppm's pass count: the samples per pixel
  void integrator(const XmlObject& o0);

  // ---------------------------------------------------------------- BSDFs and textures
  // The material of a BSDF object (made once per object); `emission` adds an area emitter's radiance.
  std::string material_name(const XmlObject& o, const json* emission);

  // Mitsuba's default radiance, intensity or irradiance: a constant 1 (white in its RGB modes).
  json default_emission();

  json default_bsdf() { return {{"type", "diffuse"}, {"reflectance", 0.5}}; }

  // Shared references can multiply: each translated BSDF, texture or shape counts.
  void count_expansion(const XmlObject& o);

  json bsdf(const XmlObject& o, const std::string& p);

  json texture(const XmlObject& o, const std::string& p);

  // ---------------------------------------------------------------- shapes
  void shape(const XmlObject& o, const glm::dmat4& parent);

  // ---------------------------------------------------------------- emitters
  void emitter(const XmlObject& o);
  // ---------------------------------------------------------------- media
  // The name in "media" of a medium object (made once per object); "" where it is left out
  // (unsupported, with --ignore-unsupported).
  std::string medium(const XmlObject& o);
  // A medium's <volume> child as our JSON (null where unsupported and skipped).
  json volume(const XmlObject& k, const std::string& pointer, bool placed);
  // A medium's coefficient (a number or a colour) as our JSON.
  json coefficient(const XmlProperty& q);
  std::map<const XmlObject*, std::string> media_;
  std::string camera_medium_;  // the sensor's
};

}  // namespace caustica::mitsuba_translation
