// Mitsuba XML property values: numbers, strings, booleans, colours and spectra, points and
// vectors, and transforms (the Parser's reading of property tags).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include "io/json_reader.h"
#include "io/mitsuba/xml_parser.h"

namespace caustica::mitsuba_xml {
namespace fs = std::filesystem;

std::vector<double> Parser::numbers(const Source& src, const pugi::xml_node& node, const std::string& text) const {
  std::vector<double> out;
  std::string s = text;
  std::replace(s.begin(), s.end(), ',', ' ');
  std::istringstream in(s);
  std::string tok;
  while (in >> tok) out.push_back(number(src, node, tok));
  return out;
}

double Parser::number(const Source& src, const pugi::xml_node& node, const std::string& tok) const {
  char* end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);
  if (tok.empty() || end != tok.c_str() + tok.size() || !std::isfinite(v)) {
    fail(src, node, "\"" + tok + "\" is not a finite number");
  }
  return v;
}

XmlProperty Parser::read_property(const Source& src, const pugi::xml_node& node, const std::string& tag, bool upgrade) {
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

void Parser::read_spectrum(const Source& src, const pugi::xml_node& node, XmlProperty& p) {
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

glm::dmat4 Parser::read_transform(const Source& src, const pugi::xml_node& node) {
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

}  // namespace caustica::mitsuba_xml
