// Mitsuba XML through pugixml into XmlObjects; see xml_tree.h.
#include "io/mitsuba/xml_tree.h"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <pugixml.hpp>
#include "io/json_reader.h"

namespace caustica {
namespace fs = std::filesystem;

const XmlProperty* XmlObject::prop(const std::string& name) const {
  for (const XmlProperty& p : props) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

bool looks_like_xml(const std::string& text) {
  size_t i = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  return i < text.size() && text[i] == '<';
}

namespace {

constexpr int kMaxIncludeDepth = 16;
constexpr int kMaxNesting = 64;
constexpr int kMaxIncludes = 1000;

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

std::string camel_to_snake(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (std::isupper(c) && i > 0 && std::islower(static_cast<unsigned char>(s[i - 1]))) out += '_';
    out += char(std::tolower(c));
  }
  return out;
}

bool is_object_tag(const std::string& t) {
  static const std::set<std::string> tags = {"bsdf",       "shape",  "emitter", "texture", "sensor", "film",
                                             "sampler",    "integrator", "rfilter", "medium", "phase", "volume",
                                             "subsurface", "scene"};
  return tags.count(t) > 0;
}

bool is_property_tag(const std::string& t) {
  static const std::set<std::string> tags = {"integer", "float", "boolean", "string",    "rgb",    "srgb",
                                             "spectrum", "blackbody", "vector", "point", "transform", "color"};
  return tags.count(t) > 0;
}

class Parser {
 public:
  Parser(const XmlOptions& options, XmlScene& scene) : scene_(scene) {
    for (const auto& [k, v] : options.defines) params_[k] = v;
  }

  void parse_main(const std::string& text, const std::string& file, const std::string& dir) {
    Source& src = load_source(text, file, dir);
    const pugi::xml_node root = root_of(src);
    auto scene = std::make_unique<XmlObject>();
    scene->tag = "scene";
    scene->dir = dir;
    scene->where = where(src, root);
    XmlObject* s = scene.get();
    scene_.objects.push_back(std::move(scene));
    scene_.version = root.attribute("version").value();
    if (scene_.version.empty()) fail(src, root, "the <scene> has no version attribute (e.g. version=\"3.0.0\")");
    read_children(src, root, *s, 0, upgrade(src, root));
    resolve_refs();
  }

 private:
  XmlScene& scene_;
  std::vector<std::unique_ptr<Source>> sources_;
  std::map<std::string, std::string> params_;
  std::map<std::string, XmlObject*> ids_;
  std::vector<PendingRef> refs_;
  int include_depth_ = 0, includes_ = 0;
  std::vector<std::string> include_stack_;  // canonical paths of the files being read

  [[noreturn]] void fail(const Source& src, const pugi::xml_node& node, const std::string& message) const {
    throw InputError(where(src, node) + ": " + message);
  }

  std::string where(const Source& src, const pugi::xml_node& node) const {
    std::string tag = "<" + std::string(node.name());
    for (const char* a : {"type", "name", "id"}) {
      const pugi::xml_attribute at = node.attribute(a);
      if (at) tag += " " + std::string(a) + "=\"" + at.value() + "\"";
    }
    return src.place(node.offset_debug()) + ": " + tag + ">";
  }

  Source& load_source(const std::string& text, const std::string& file, const std::string& dir) {
    auto src = std::make_unique<Source>();
    src->name = file;
    src->dir = dir;
    src->text = text;
    src->index_lines();
    const pugi::xml_parse_result result = src->doc.load_buffer(src->text.data(), src->text.size());
    if (!result) {
      throw InputError(src->place(result.offset) + ": malformed XML: " + result.description());
    }
    sources_.push_back(std::move(src));
    return *sources_.back();
  }

  pugi::xml_node root_of(const Source& src) const {
    const pugi::xml_node root = src.doc.document_element();
    if (!root) throw InputError(src.name + ": the XML document has no element");
    if (std::string(root.name()) != "scene") {
      throw InputError(where(src, root) + ": the root element is <" + root.name() + ">; a Mitsuba scene's is <scene>");
    }
    return root;
  }

  // 0.6 scenes (version < 2) name parameters in camelCase.
  bool upgrade(const Source& src, const pugi::xml_node& root) const {
    const std::string v = root.attribute("version").value();
    int major = 0;
    if (std::sscanf(v.c_str(), "%d", &major) != 1) fail(src, root, "cannot read the version \"" + v + "\" (e.g. 3.0.0)");
    return major < 2;
  }

  // Replaces each $name (letters, digits, underscores) by its value; "\\$" is a dollar sign.
  // Mitsuba replaces the longest defined names first, so that $r also matched inside $rough; a
  // whole-name match makes $rough with only r defined an error instead of "0.5ough".
  std::string subst(const Source& src, const pugi::xml_node& node, const std::string& value) const {
    if (value.find('$') == std::string::npos) return value;
    std::string out;
    for (size_t i = 0; i < value.size(); ++i) {
      if (value[i] == '\\' && i + 1 < value.size() && value[i + 1] == '$') {
        out += '$';
        ++i;
        continue;
      }
      if (value[i] != '$') {
        out += value[i];
        continue;
      }
      size_t end = i + 1;
      while (end < value.size() && (std::isalnum(static_cast<unsigned char>(value[end])) || value[end] == '_')) ++end;
      const std::string name = value.substr(i + 1, end - i - 1);
      const auto it = params_.find(name);
      if (name.empty()) fail(src, node, "a \"$\" without a parameter name in \"" + value + "\"");
      if (it == params_.end()) {
        fail(src, node, "unknown parameter \"$" + name + "\": no <default name=\"" + name + "\" value=...> and no -D " + name + "=...");
      }
      out += it->second;
      i = end - 1;
    }
    return out;
  }

  std::string attr(const Source& src, const pugi::xml_node& node, const char* name) const {
    return subst(src, node, node.attribute(name).value());
  }
  std::string required_attr(const Source& src, const pugi::xml_node& node, const char* name) const {
    if (!node.attribute(name)) fail(src, node, std::string("missing attribute \"") + name + "\"");
    return attr(src, node, name);
  }

  void check_attributes(const Source& src, const pugi::xml_node& node, std::initializer_list<const char*> known) const {
    for (const pugi::xml_attribute a : node.attributes()) {
      bool ok = false;
      for (const char* k : known) ok = ok || std::string(a.name()) == k;
      if (!ok) fail(src, node, "unknown attribute \"" + std::string(a.name()) + "\"");
    }
  }

  // Numbers separated by commas and/or white space.
  std::vector<double> numbers(const Source& src, const pugi::xml_node& node, const std::string& text) const {
    std::vector<double> out;
    std::string s = text;
    std::replace(s.begin(), s.end(), ',', ' ');
    std::istringstream in(s);
    std::string tok;
    while (in >> tok) out.push_back(number(src, node, tok));
    return out;
  }

  double number(const Source& src, const pugi::xml_node& node, const std::string& tok) const {
    char* end = nullptr;
    const double v = std::strtod(tok.c_str(), &end);
    if (tok.empty() || end != tok.c_str() + tok.size() || !std::isfinite(v)) {
      fail(src, node, "\"" + tok + "\" is not a finite number");
    }
    return v;
  }

  glm::dvec3 vec3(const Source& src, const pugi::xml_node& node, const std::string& text, const char* what) const {
    const std::vector<double> v = numbers(src, node, text);
    if (v.size() != 3) fail(src, node, std::string(what) + ": expected 3 numbers \"x, y, z\", found \"" + text + "\"");
    return {v[0], v[1], v[2]};
  }

  // value="x, y, z" or x=, y=, z= attributes (missing ones `fallback`).
  glm::dvec3 xyz(const Source& src, const pugi::xml_node& node, double fallback) const {
    if (node.attribute("value")) {
      if (node.attribute("x") || node.attribute("y") || node.attribute("z")) fail(src, node, "give value or x, y, z, not both");
      return vec3(src, node, attr(src, node, "value"), "value");
    }
    glm::dvec3 v(fallback);
    const char* names[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
      if (node.attribute(names[i])) v[i] = number(src, node, attr(src, node, names[i]));
    }
    return v;
  }

  void read_children(Source& src, const pugi::xml_node& node, XmlObject& obj, int depth, bool upgrade) {
    if (depth > kMaxNesting) fail(src, node, "objects nested deeper than " + std::to_string(kMaxNesting) + " levels");
    for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling()) {
      if (c.type() != pugi::node_element) continue;
      std::string tag = c.name();
      if (upgrade && tag == "lookAt") tag = "lookat";
      if (tag == "default") {
        check_attributes(src, c, {"name", "value"});
        const std::string name = c.attribute("name").value();
        if (name.empty()) fail(src, c, "a <default> needs a name");
        if (!c.attribute("value")) fail(src, c, "a <default> needs a value");
        if (!params_.count(name)) params_[name] = attr(src, c, "value");
      } else if (tag == "include") {
        include(src, c, obj, depth, upgrade);
      } else if (tag == "path") {
        if (&obj != scene_.objects.front().get()) fail(src, c, "<path> belongs directly in the <scene>");
        fs::path dir = required_attr(src, c, "value");
        if (dir.is_relative()) dir = fs::path(src.dir) / dir;
        std::error_code ec;
        if (!fs::is_directory(dir, ec)) fail(src, c, "the folder " + dir.string() + " does not exist");
        scene_.search_paths.insert(scene_.search_paths.begin(), dir.string());
      } else if (tag == "alias") {
        check_attributes(src, c, {"id", "as"});
        const std::string id = required_attr(src, c, "id"), as = required_attr(src, c, "as");
        const auto it = ids_.find(id);
        if (it == ids_.end()) fail(src, c, "<alias> of an unknown id \"" + id + "\"");
        if (!ids_.emplace(as, it->second).second) fail(src, c, "the id \"" + as + "\" is already taken");
      } else if (tag == "ref") {
        check_attributes(src, c, {"id", "name"});
        XmlChild child;
        child.name = prop_name(src, c, upgrade);
        child.where = where(src, c);
        obj.children.push_back(child);
        refs_.push_back({&obj, obj.children.size() - 1, required_attr(src, c, "id")});
      } else if (is_property_tag(tag)) {
        obj.props.push_back(read_property(src, c, tag, upgrade));
        for (const XmlProperty& p : obj.props) {
          if (&p != &obj.props.back() && p.name == obj.props.back().name) {
            fail(src, c, "the property \"" + p.name + "\" is given twice (first at " + p.where + ")");
          }
        }
      } else if (is_object_tag(tag) && tag != "scene") {
        auto o = std::make_unique<XmlObject>();
        o->tag = tag;
        o->type = attr(src, c, "type");
        o->id = attr(src, c, "id");
        o->where = where(src, c);
        o->dir = src.dir;
        if (o->type.empty() && tag != "scene") fail(src, c, "<" + tag + "> needs a type attribute");
        XmlObject* raw = o.get();
        scene_.objects.push_back(std::move(o));
        if (!raw->id.empty() && !ids_.emplace(raw->id, raw).second) {
          fail(src, c, "the id \"" + raw->id + "\" is already taken (by " + ids_[raw->id]->where + ")");
        }
        XmlChild child;
        child.object = raw;
        child.name = prop_name(src, c, upgrade);
        child.where = raw->where;
        obj.children.push_back(child);
        read_children(src, c, *raw, depth + 1, upgrade);
      } else {
        fail(src, c, "unexpected element <" + tag + ">");
      }
    }
  }

  std::string prop_name(const Source& src, const pugi::xml_node& node, bool upgrade) const {
    const std::string n = attr(src, node, "name");
    return upgrade ? camel_to_snake(n) : n;
  }

  void include(Source& src, const pugi::xml_node& node, XmlObject& obj, int depth, bool) {
    check_attributes(src, node, {"filename", "name"});
    const std::string name = required_attr(src, node, "filename");
    if (include_depth_ >= kMaxIncludeDepth) fail(src, node, "includes nested deeper than " + std::to_string(kMaxIncludeDepth) + " (a cycle?)");
    const std::string path = resolve(src, name);
    if (path.empty()) fail(src, node, "included file not found: " + name);
    std::error_code canon_ec;
    const std::string canonical = fs::weakly_canonical(path, canon_ec).string();
    if (std::find(include_stack_.begin(), include_stack_.end(), canonical) != include_stack_.end()) {
      fail(src, node, "the file " + path + " includes itself");
    }
    if (++includes_ > kMaxIncludes) fail(src, node, "more than " + std::to_string(kMaxIncludes) + " includes in all");
    std::error_code ec;
    // Only regular files: a FIFO or a device would block or never end.
    if (!fs::is_regular_file(path, ec)) fail(src, node, "the included path is not a regular file: " + path);
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(src, node, "cannot read the included file " + path);
    std::ostringstream ss;
    ss << in.rdbuf();
    Source& inc = load_source(ss.str(), path, fs::path(path).parent_path().string());
    const pugi::xml_node root = inc.doc.document_element();
    if (!root) throw InputError(path + ": the XML document has no element");
    ++include_depth_;
    include_stack_.push_back(canonical);
    if (std::string(root.name()) == "scene") {
      read_children(inc, root, obj, depth, upgrade(inc, root));
    } else {
      // A single object: as if written here (with the <include>'s name, if any).
      read_children(inc, root.parent(), obj, depth, false);
      if (node.attribute("name") && !obj.children.empty()) obj.children.back().name = attr(src, node, "name");
    }
    include_stack_.pop_back();
    --include_depth_;
  }

  // A file named in the scene: as given if absolute, else next to the file naming it, else in
  // the <path> folders.
  std::string resolve(const Source& src, const std::string& name) const {
    std::error_code ec;
    const fs::path p(name);
    if (p.is_absolute()) return fs::exists(p, ec) ? p.string() : std::string();
    const fs::path here = fs::path(src.dir) / p;
    if (fs::exists(here, ec)) return here.string();
    // An included file's paths may be relative to the main scene, as Mitsuba's resolver allows.
    const fs::path main = fs::path(scene_.root().dir) / p;
    if (fs::exists(main, ec)) return main.string();
    for (const std::string& dir : scene_.search_paths) {
      if (fs::exists(fs::path(dir) / p, ec)) return (fs::path(dir) / p).string();
    }
    return {};
  }

  XmlProperty read_property(const Source& src, const pugi::xml_node& node, const std::string& tag, bool upgrade) {
    XmlProperty p;
    p.name = prop_name(src, node, upgrade);
    p.where = where(src, node);
    if (p.name.empty()) fail(src, node, "a property needs a name");
    auto value = [&]() { return required_attr(src, node, "value"); };
    if (tag == "integer") {
      check_attributes(src, node, {"name", "value"});
      p.kind = XmlProperty::Integer;
      const std::string v = value();
      char* end = nullptr;
      const long long i = std::strtoll(v.c_str(), &end, 10);
      if (v.empty() || end != v.c_str() + v.size()) fail(src, node, "\"" + v + "\" is not an integer");
      p.number = double(i);
    } else if (tag == "float") {
      check_attributes(src, node, {"name", "value"});
      p.kind = XmlProperty::Float;
      p.number = number(src, node, value());
    } else if (tag == "boolean") {
      check_attributes(src, node, {"name", "value"});
      p.kind = XmlProperty::Boolean;
      std::string v = value();
      std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return char(std::tolower(c)); });
      if (v != "true" && v != "false") fail(src, node, "\"" + v + "\" is not a boolean (true or false)");
      p.boolean = v == "true";
    } else if (tag == "string") {
      check_attributes(src, node, {"name", "value"});
      p.kind = XmlProperty::String;
      p.text = value();
    } else if (tag == "rgb" || tag == "color" || tag == "srgb") {
      check_attributes(src, node, {"name", "value", "intent"});
      p.kind = XmlProperty::Rgb;
      const std::string v = value();
      if (tag == "srgb" && !v.empty() && v[0] == '#') {
        if (v.size() != 7) fail(src, node, "\"" + v + "\" is not a colour #rrggbb");
        for (int i = 0; i < 3; ++i) {
          char* end = nullptr;
          const std::string hex = v.substr(1 + 2 * size_t(i), 2);
          const long c = std::strtol(hex.c_str(), &end, 16);
          if (end != hex.c_str() + 2) fail(src, node, "\"" + v + "\" is not a colour #rrggbb");
          p.vec[i] = double(c) / 255.0;
        }
      } else {
        const std::vector<double> c = numbers(src, node, v);
        if (c.size() == 1) p.vec = glm::dvec3(c[0]);
        else if (c.size() == 3) p.vec = {c[0], c[1], c[2]};
        else fail(src, node, "expected 3 numbers \"r, g, b\" (or one), found \"" + v + "\"");
      }
      if (tag == "srgb") {
        for (int i = 0; i < 3; ++i) {
          const double c = p.vec[i];
          p.vec[i] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
        }
      }
    } else if (tag == "spectrum") {
      read_spectrum(src, node, p);
    } else if (tag == "blackbody") {
      check_attributes(src, node, {"name", "temperature", "scale"});
      p.kind = XmlProperty::Blackbody;
      std::string t = required_attr(src, node, "temperature");
      if (!t.empty() && (t.back() == 'K' || t.back() == 'k')) t.pop_back();
      p.number = number(src, node, t);
      if (node.attribute("scale")) p.scale = number(src, node, attr(src, node, "scale"));
      if (!(p.number > 0.0)) fail(src, node, "the temperature must be positive");
    } else if (tag == "vector" || tag == "point") {
      check_attributes(src, node, {"name", "value", "x", "y", "z"});
      p.kind = XmlProperty::Vector;
      p.vec = xyz(src, node, 0.0);
    } else {  // transform
      check_attributes(src, node, {"name"});
      p.kind = XmlProperty::Transform;
      p.matrix = read_transform(src, node);
    }
    return p;
  }

  void read_spectrum(const Source& src, const pugi::xml_node& node, XmlProperty& p) {
    if (node.attribute("type")) {
      // Mitsuba 3's <spectrum type="blackbody" name="radiance"><float name="temperature" .../></spectrum>.
      const std::string type = attr(src, node, "type");
      if (type != "blackbody") fail(src, node, "unknown spectrum type \"" + type + "\" (known: blackbody)");
      p.kind = XmlProperty::Blackbody;
      bool have = false;
      for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling()) {
        if (c.type() != pugi::node_element) continue;
        const std::string n = c.attribute("name").value();
        if (std::string(c.name()) != "float" || (n != "temperature" && n != "scale")) {
          fail(src, c, "a blackbody spectrum takes <float name=\"temperature\"> and <float name=\"scale\">");
        }
        (n == "temperature" ? p.number : p.scale) = number(src, c, required_attr(src, c, "value"));
        have = have || n == "temperature";
      }
      if (!have || !(p.number > 0.0)) fail(src, node, "a blackbody spectrum needs a positive temperature");
      return;
    }
    check_attributes(src, node, {"name", "value", "filename"});
    p.kind = XmlProperty::Spectrum;
    std::string text;
    if (node.attribute("filename")) {
      if (node.attribute("value")) fail(src, node, "give value or filename, not both");
      const std::string path = resolve(src, attr(src, node, "filename"));
      if (path.empty()) fail(src, node, "spectrum file not found: " + attr(src, node, "filename"));
      std::error_code ec;
      if (!fs::is_regular_file(path, ec)) fail(src, node, "the spectrum path is not a regular file: " + path);
      if (fs::file_size(path, ec) > (size_t(1) << 24)) fail(src, node, "the spectrum file " + path + " is larger than 16 MiB");
      std::ifstream in(path);
      std::string line;
      while (std::getline(in, line)) {
        const size_t hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        std::istringstream ls(line);
        std::string wl, v;
        if (!(ls >> wl)) continue;
        if (!(ls >> v)) fail(src, node, path + ": expected \"wavelength value\" per line, found \"" + line + "\"");
        text += (text.empty() ? "" : ", ") + wl + ":" + v;
      }
    } else {
      text = required_attr(src, node, "value");
    }
    if (text.find(':') == std::string::npos) {
      const std::vector<double> v = numbers(src, node, text);
      if (v.size() != 1) fail(src, node, "expected one number or wavelength:value pairs, found \"" + text + "\"");
      p.number = v[0];
      return;
    }
    std::string s = text;
    std::replace(s.begin(), s.end(), ',', ' ');
    std::istringstream in(s);
    std::string tok;
    while (in >> tok) {
      const size_t colon = tok.find(':');
      if (colon == std::string::npos) fail(src, node, "\"" + tok + "\" is not a wavelength:value pair");
      const double wl = number(src, node, tok.substr(0, colon)), v = number(src, node, tok.substr(colon + 1));
      if (!p.samples.empty() && !(wl > p.samples.back().first)) fail(src, node, "the wavelengths must increase");
      p.samples.emplace_back(wl, v);
    }
  }

  glm::dmat4 read_transform(const Source& src, const pugi::xml_node& node) {
    glm::dmat4 m(1.0);
    for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling()) {
      if (c.type() != pugi::node_element) continue;
      std::string op = c.name();
      if (op == "lookAt") op = "lookat";
      glm::dmat4 t(1.0);
      if (op == "translate") {
        check_attributes(src, c, {"value", "x", "y", "z"});
        const glm::dvec3 v = xyz(src, c, 0.0);
        t[3] = glm::dvec4(v, 1.0);
      } else if (op == "scale") {
        check_attributes(src, c, {"value", "x", "y", "z"});
        glm::dvec3 v;
        if (c.attribute("value") && numbers(src, c, attr(src, c, "value")).size() == 1) {
          v = glm::dvec3(numbers(src, c, attr(src, c, "value"))[0]);
        } else {
          v = xyz(src, c, 1.0);
        }
        t[0][0] = v.x, t[1][1] = v.y, t[2][2] = v.z;
      } else if (op == "rotate") {
        check_attributes(src, c, {"value", "x", "y", "z", "angle"});
        const glm::dvec3 axis = xyz(src, c, 0.0);
        const double angle = number(src, c, required_attr(src, c, "angle")) * 3.14159265358979323846 / 180.0;
        const double len = glm::length(axis);
        if (!(len > 0.0)) fail(src, c, "the rotation axis is zero");
        const glm::dvec3 a = axis / len;
        const double co = std::cos(angle), si = std::sin(angle);
        glm::dmat3 r;
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) r[j][i] = a[i] * a[j] * (1.0 - co) + (i == j ? co : 0.0);
        }
        r[1][0] -= a.z * si, r[2][0] += a.y * si;  // row 0: -z s at column 1, +y s at column 2
        r[0][1] += a.z * si, r[2][1] -= a.x * si;
        r[0][2] -= a.y * si, r[1][2] += a.x * si;
        t = glm::dmat4(r);
      } else if (op == "matrix") {
        check_attributes(src, c, {"value"});
        const std::vector<double> v = numbers(src, c, required_attr(src, c, "value"));
        if (v.size() != 16 && v.size() != 9) fail(src, c, "a matrix needs 16 numbers (or 9), row by row");
        const int n = v.size() == 16 ? 4 : 3;
        for (int row = 0; row < n; ++row) {
          for (int col = 0; col < n; ++col) t[col][row] = v[size_t(row * n + col)];
        }
      } else if (op == "lookat") {
        check_attributes(src, c, {"origin", "target", "up"});
        const glm::dvec3 o = vec3(src, c, required_attr(src, c, "origin"), "origin");
        const glm::dvec3 target = vec3(src, c, required_attr(src, c, "target"), "target");
        glm::dvec3 up = c.attribute("up") ? vec3(src, c, attr(src, c, "up"), "up") : glm::dvec3(0, 1, 0);
        const glm::dvec3 d = target - o;
        if (!(glm::length(d) > 0.0)) fail(src, c, "origin and target are the same point");
        const glm::dvec3 dir = glm::normalize(d);
        if (!c.attribute("up") && std::abs(dir.y) > 0.999) up = glm::dvec3(0, 0, 1);
        const glm::dvec3 left0 = glm::cross(up, dir);
        if (!(glm::length(left0) > 1e-9)) fail(src, c, "up is parallel to the viewing direction");
        const glm::dvec3 left = glm::normalize(left0), new_up = glm::cross(dir, left);
        t[0] = glm::dvec4(left, 0.0);
        t[1] = glm::dvec4(new_up, 0.0);
        t[2] = glm::dvec4(dir, 0.0);
        t[3] = glm::dvec4(o, 1.0);
      } else {
        fail(src, c, "unknown transform <" + op + "> (known: translate, rotate, scale, matrix, lookat)");
      }
      m = t * m;
    }
    return m;
  }

  void resolve_refs() {
    for (const PendingRef& r : refs_) {
      XmlChild& c = r.owner->children[r.child];
      const auto it = ids_.find(r.id);
      if (it == ids_.end()) {
        std::string known;
        for (const auto& kv : ids_) known += (known.empty() ? "" : ", ") + kv.first;
        throw InputError(c.where + ": reference to an unknown id \"" + r.id + "\"" +
                         (known.empty() ? " (the scene defines no ids)" : " (known: " + known + ")"));
      }
      c.object = it->second;
      if (c.object == r.owner) throw InputError(c.where + ": an object cannot refer to itself");
    }
    check_cycles();
  }

  // References must not form a cycle (a twosided BSDF inside itself, a group holding its own
  // instance): the translation would never end.
  void check_cycles() const {
    enum State : char { New, Open, Done };
    std::map<const XmlObject*, State> state;
    struct Frame {
      const XmlObject* o;
      size_t next;
    };
    for (const auto& start : scene_.objects) {
      if (state[start.get()] != New) continue;
      std::vector<Frame> stack = {{start.get(), 0}};
      state[start.get()] = Open;
      while (!stack.empty()) {
        Frame& f = stack.back();
        if (f.next == f.o->children.size()) {
          state[f.o] = Done;
          stack.pop_back();
          continue;
        }
        const XmlChild& c = f.o->children[f.next++];
        State& s = state[c.object];
        if (s == Open) throw InputError(c.where + ": this reference closes a cycle (an object inside itself)");
        if (s == New) {
          s = Open;
          stack.push_back({c.object, 0});
        }
      }
    }
  }
};

}  // namespace

XmlScene parse_mitsuba_xml(const std::string& text, const std::string& file, const std::string& dir,
                           const XmlOptions& options) {
  XmlScene scene;
  Parser parser(options, scene);
  parser.parse_main(text, file, dir.empty() ? "." : dir);
  return scene;
}

}  // namespace caustica
