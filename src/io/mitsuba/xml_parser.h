// What the Mitsuba XML reader's files share: the Parser, whose member functions are defined in
// xml_tree.cpp (files, includes, objects, references) and xml_values.cpp (property values:
// numbers, colours and spectra, vectors, transforms), and the Source it reads from. Internal
// to src/io/mitsuba.
#pragma once
#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>
#include <glm/glm.hpp>
#include <pugixml.hpp>
#include "io/mitsuba/xml_tree.h"

namespace caustica::mitsuba_xml {


inline constexpr int kMaxIncludeDepth = 16;
inline constexpr int kMaxNesting = 64;
inline constexpr int kMaxIncludes = 1000;

// One file of the scene (the main file or an include) and what is needed to place errors in it.
struct Source {
  std::string name, text;
  std::string dir;  // relative paths in this file resolve against it
  std::vector<size_t> line_starts;
  pugi::xml_document doc;

  void index_lines() {
    line_starts.push_back(0);
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n') line_starts.push_back(i + 1);
    }
  }
  std::string place(ptrdiff_t offset) const {
    if (offset < 0) return name;
    const size_t o = size_t(offset);
    const size_t line = size_t(std::upper_bound(line_starts.begin(), line_starts.end(), o) - line_starts.begin());
    return name + ":" + std::to_string(line) + ":" + std::to_string(o - line_starts[line - 1] + 1);
  }
};

struct PendingRef {
  XmlObject* owner;
  size_t child;
  std::string id;
};

std::string camel_to_snake(const std::string& s);
bool is_object_tag(const std::string& t);
bool is_property_tag(const std::string& t);

class Parser {
 public:
  Parser(const XmlOptions& options, XmlScene& scene) : scene_(scene) {
    for (const auto& [k, v] : options.defines) params_[k] = v;
  }

  void parse_main(const std::string& text, const std::string& file, const std::string& dir);

 private:
  XmlScene& scene_;
  std::vector<std::unique_ptr<Source>> sources_;
  std::map<std::string, std::string> params_;
  std::map<std::string, XmlObject*> ids_;
  std::vector<PendingRef> refs_;
  int include_depth_ = 0, includes_ = 0;
  mutable size_t expanded_bytes_ = 0;  // characters that $name substitution has produced so far
  std::vector<std::string> include_stack_;  // canonical paths of the files being read

  [[noreturn]] void fail(const Source& src, const pugi::xml_node& node, const std::string& message) const;

  std::string where(const Source& src, const pugi::xml_node& node) const;

  Source& load_source(const std::string& text, const std::string& file, const std::string& dir);

  pugi::xml_node root_of(const Source& src) const;

  // 0.6 scenes (version < 2) name parameters in camelCase.
  bool upgrade(const Source& src, const pugi::xml_node& root) const;

  // Replaces each $name (letters, digits, underscores) by its value; "\\$" is a dollar sign.
  // Mitsuba replaces the longest defined names first, so that $r also matched inside $rough; a
  // whole-name match makes $rough with only r defined an error instead of "0.5ough".
  // Bounded, so that <default> values that double each other cannot exhaust memory: one value
  // expands to at most kMaxExpandedValue characters, a whole scene to kMaxExpandedTotal.
  std::string subst(const Source& src, const pugi::xml_node& node, const std::string& value) const;

  std::string attr(const Source& src, const pugi::xml_node& node, const char* name) const;
  std::string required_attr(const Source& src, const pugi::xml_node& node, const char* name) const;

  void check_attributes(const Source& src, const pugi::xml_node& node, std::initializer_list<const char*> known) const;

  // Numbers separated by commas and/or white space.
  std::vector<double> numbers(const Source& src, const pugi::xml_node& node, const std::string& text) const;

  double number(const Source& src, const pugi::xml_node& node, const std::string& tok) const;

  glm::dvec3 vec3(const Source& src, const pugi::xml_node& node, const std::string& text, const char* what) const;

  // value="x, y, z" or x=, y=, z= attributes (missing ones `fallback`).
  glm::dvec3 xyz(const Source& src, const pugi::xml_node& node, double fallback) const;

  void read_children(Source& src, const pugi::xml_node& node, XmlObject& obj, int depth, bool upgrade);

  std::string prop_name(const Source& src, const pugi::xml_node& node, bool upgrade) const;

  void include(Source& src, const pugi::xml_node& node, XmlObject& obj, int depth, bool);

  // A file named in the scene: as given if absolute, else next to the file naming it, else in
  // the <path> folders.
  std::string resolve(const Source& src, const std::string& name) const;

  XmlProperty read_property(const Source& src, const pugi::xml_node& node, const std::string& tag, bool upgrade);

  void read_spectrum(const Source& src, const pugi::xml_node& node, XmlProperty& p);

  glm::dmat4 read_transform(const Source& src, const pugi::xml_node& node);

  void resolve_refs();

  // References must not form a cycle (a twosided BSDF inside itself, a group holding its own
  // instance): the translation would never end.
  void check_cycles() const;
};

}  // namespace caustica::mitsuba_xml
