// Mitsuba scene files (0.6 to 3.x) read into a tree of plugin objects and typed properties:
// <default>/$name substitution (-D on the command line wins), <include>, <path>, ids and <ref>s,
// <alias>, the 0.6 names upgraded (camelCase to snake_case, <lookAt>), transforms composed in
// order. The meaning of the plugins is decided later (translate.h). Errors name file:line:column.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>
#include "core/math.h"

namespace caustica {

struct XmlOptions {
  std::vector<std::pair<std::string, std::string>> defines;  // -D name=value, before any <default>
};

struct XmlProperty {
  enum Kind { Integer, Float, Boolean, String, Rgb, Spectrum, Blackbody, Vector, Transform };
  Kind kind = Float;
  std::string name;
  std::string where;  // "scene.xml:12:5: <float name="alpha">"
  double number = 0.0;  // Integer, Float, a constant Spectrum, Blackbody's temperature
  bool boolean = false;
  std::string text;
  glm::dvec3 vec{0.0};   // Vector, Rgb (linear)
  glm::dmat4 matrix{1.0};  // Transform
  std::vector<std::pair<double, double>> samples;  // Spectrum: (nm, value), empty for a constant
  double scale = 1.0;  // Blackbody
};

struct XmlObject;

// A nested object or a <ref>: `name` is the property name it fills (may be empty).
struct XmlChild {
  const XmlObject* object = nullptr;
  std::string name;
  std::string where;
};

struct XmlObject {
  std::string tag, type, id;
  std::string where;  // "scene.xml:12:5: <bsdf type="diffuse">"
  std::string dir;    // the folder of the file it was read from: relative paths resolve against it
  std::vector<XmlProperty> props;
  std::vector<XmlChild> children;

  const XmlProperty* prop(const std::string& name) const;
};

struct XmlScene {
  std::vector<std::unique_ptr<XmlObject>> objects;  // objects[0] is the <scene>
  std::vector<std::string> search_paths;            // from <path>, first = first tried
  std::string version;
  const XmlObject& root() const { return *objects.front(); }
};

// True when the text's first element is XML (it starts with '<' after a BOM and white space).
bool looks_like_xml(const std::string& text);

// Throws InputError with file:line:column. `file` names the text in messages; relative paths in it
// resolve against `dir` (those in included files against their own folders).
XmlScene parse_mitsuba_xml(const std::string& text, const std::string& file, const std::string& dir,
                           const XmlOptions& options);

}  // namespace caustica
