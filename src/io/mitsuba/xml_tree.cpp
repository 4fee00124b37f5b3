// Mitsuba XML through pugixml into XmlObjects; see xml_tree.h. This file: files, includes,
// objects and references; property values are read in xml_values.cpp.
#include "io/file_bytes.h"
#include "io/mitsuba/xml_tree.h"
#include "io/mitsuba/xml_parser.h"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
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

}  // namespace caustica

namespace caustica::mitsuba_xml {
namespace fs = std::filesystem;

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

void Parser::parse_main(const std::string& text, const std::string& file, const std::string& dir) {
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
  // The main file too may be included again, by itself or another file.
  std::error_code ec;
  if (fs::is_regular_file(file, ec)) include_stack_.push_back(fs::weakly_canonical(file, ec).string());
  read_children(src, root, *s, 0, upgrade(src, root));
  resolve_refs();
}

void Parser::fail(const Source& src, const pugi::xml_node& node, const std::string& message) const {
  throw InputError(where(src, node) + ": " + message);
}

std::string Parser::where(const Source& src, const pugi::xml_node& node) const {
  std::string tag = "<" + std::string(node.name());
  for (const char* a : {"type", "name", "id"}) {
    const pugi::xml_attribute at = node.attribute(a);
    if (at) tag += " " + std::string(a) + "=\"" + at.value() + "\"";
  }
  return src.place(node.offset_debug()) + ": " + tag + ">";
}

Source& Parser::load_source(const std::string& text, const std::string& file, const std::string& dir) {
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

pugi::xml_node Parser::root_of(const Source& src) const {
  const pugi::xml_node root = src.doc.document_element();
  if (!root) throw InputError(src.name + ": the XML document has no element");
  if (std::string(root.name()) != "scene") {
    throw InputError(where(src, root) + ": the root element is <" + root.name() + ">; a Mitsuba scene's is <scene>");
  }
  return root;
}

bool Parser::upgrade(const Source& src, const pugi::xml_node& root) const {
  const std::string v = root.attribute("version").value();
  int major = 0;
  if (std::sscanf(v.c_str(), "%d", &major) != 1) fail(src, root, "cannot read the version \"" + v + "\" (e.g. 3.0.0)");
  return major < 2;
}

namespace {
constexpr size_t kMaxExpandedValue = size_t(1) << 20, kMaxExpandedTotal = size_t(64) << 20;
}  // namespace

std::string Parser::subst(const Source& src, const pugi::xml_node& node, const std::string& value) const {
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
    if (out.size() + it->second.size() > kMaxExpandedValue) {
      fail(src, node, "\"$" + name + "\" expands this value past " + std::to_string(kMaxExpandedValue >> 20) +
                          " MiB (do <default> values double each other?)");
    }
    out += it->second;
    expanded_bytes_ += it->second.size();
    if (expanded_bytes_ > kMaxExpandedTotal) {
      fail(src, node, "$name substitution has produced more than " + std::to_string(kMaxExpandedTotal >> 20) +
                          " MiB of text in this scene (do <default> values double each other?)");
    }
    i = end - 1;
  }
  return out;
}

std::string Parser::attr(const Source& src, const pugi::xml_node& node, const char* name) const {
  return subst(src, node, node.attribute(name).value());
}

std::string Parser::required_attr(const Source& src, const pugi::xml_node& node, const char* name) const {
  if (!node.attribute(name)) fail(src, node, std::string("missing attribute \"") + name + "\"");
  return attr(src, node, name);
}

void Parser::check_attributes(const Source& src, const pugi::xml_node& node, std::initializer_list<const char*> known) const {
  for (const pugi::xml_attribute a : node.attributes()) {
    bool ok = false;
    for (const char* k : known) ok = ok || std::string(a.name()) == k;
    if (!ok) fail(src, node, "unknown attribute \"" + std::string(a.name()) + "\"");
  }
}

glm::dvec3 Parser::vec3(const Source& src, const pugi::xml_node& node, const std::string& text, const char* what) const {
  const std::vector<double> v = numbers(src, node, text);
  if (v.size() != 3) fail(src, node, std::string(what) + ": expected 3 numbers \"x, y, z\", found \"" + text + "\"");
  return {v[0], v[1], v[2]};
}

glm::dvec3 Parser::xyz(const Source& src, const pugi::xml_node& node, double fallback) const {
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

void Parser::read_children(Source& src, const pugi::xml_node& node, XmlObject& obj, int depth, bool upgrade) {
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
      const fs::path value = required_attr(src, c, "value");
      // As Mitsuba 3: next to the file naming it, then through the file resolver (the main
      // scene's folder, then the <path> folders so far).
      std::vector<fs::path> tried = {value};
      if (value.is_relative()) {
        tried = {fs::path(src.dir) / value};
        if (src.dir != scene_.root().dir) tried.push_back(fs::path(scene_.root().dir) / value);
        for (const std::string& d : scene_.search_paths) tried.push_back(fs::path(d) / value);
      }
      std::error_code ec;
      const auto found = std::find_if(tried.begin(), tried.end(), [&](const fs::path& d) { return fs::is_directory(d, ec); });
      if (found == tried.end()) {
        std::string all;
        for (const fs::path& t : tried) all += (all.empty() ? "" : ", ") + t.string();
        fail(src, c, tried.size() == 1 ? "the folder " + all + " does not exist" : "the folder does not exist: tried " + all);
      }
      scene_.search_paths.insert(scene_.search_paths.begin(), found->string());
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
      // Plugin names in lower case: Mitsuba finds plugins by file name, so "Rectangle" (as in
      // some exported scenes) loads where the file system ignores case.
      o->type = attr(src, c, "type");
      for (char& ch : o->type) ch = char(std::tolower(static_cast<unsigned char>(ch)));
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

std::string Parser::prop_name(const Source& src, const pugi::xml_node& node, bool upgrade) const {
  const std::string n = attr(src, node, "name");
  return upgrade ? camel_to_snake(n) : n;
}

void Parser::include(Source& src, const pugi::xml_node& node, XmlObject& obj, int depth, bool) {
  check_attributes(src, node, {"filename", "name"});
  const std::string name = required_attr(src, node, "filename");
  if (include_depth_ >= kMaxIncludeDepth) fail(src, node, "includes nested deeper than " + std::to_string(kMaxIncludeDepth) + " (a cycle?)");
  const std::string path = resolve(src, name);
  if (path.empty()) fail(src, node, "included file not found: " + name);
  std::error_code canon_ec;
  const std::string canonical = fs::weakly_canonical(path, canon_ec).string();
  if (std::find(include_stack_.begin(), include_stack_.end(), canonical) != include_stack_.end()) {
    fail(src, node, "including " + path + " here makes a cycle: that file is being read already (it includes itself, "
                    "directly or through other files)");
  }
  if (++includes_ > kMaxIncludes) fail(src, node, "more than " + std::to_string(kMaxIncludes) + " includes in all");
  std::error_code ec;
  // Only regular files: a FIFO or a device would block or never end.
  if (!fs::is_regular_file(path, ec)) fail(src, node, "the included path is not a regular file: " + path);
  std::string text;
  try {
    text = read_file_bytes(path, "included file");
  } catch (const InputError& e) {
    fail(src, node, e.what());
  }
  Source& inc = load_source(text, path, fs::path(path).parent_path().string());
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

std::string Parser::resolve(const Source& src, const std::string& name) const {
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

void Parser::resolve_refs() {
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

void Parser::check_cycles() const {
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

}  // namespace caustica::mitsuba_xml

namespace caustica {


XmlScene parse_mitsuba_xml(const std::string& text, const std::string& file, const std::string& dir,
                           const XmlOptions& options) {
  XmlScene scene;
  mitsuba_xml::Parser parser(options, scene);
  parser.parse_main(text, file, dir.empty() ? "." : dir);
  return scene;
}

}  // namespace caustica
