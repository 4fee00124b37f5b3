// PLY meshes (ASCII, binary little- and big-endian): vertex x y z, optional nx ny nz and
// u v (or s t, texture_u texture_v, texture_s texture_t), faces as lists of vertex indices
// (vertex_indices or vertex_index), polygons split into fans. Other vertex and face properties
// become mesh attributes as Mitsuba 3's PLY reader groups them (mesh_attribute_groups below);
// other elements are skipped. Every count and index is checked against the file before
// anything is allocated.
//
// We tried Assimp (Debian's libassimp-dev 5.2.5) first: on a binary PLY cut short it crashed
// (SIGSEGV in its post-processing) or spun without end, and a system library cannot be fuzzed
// with our instrumentation. This reader is small, checked, and fuzzed (fuzz/mesh_fuzzer.cpp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <set>
#include "io/file_bytes.h"
#include "core/error.h"
#include "core/image.h"
#include "io/meshes/mesh_file.h"

namespace caustica {
namespace {

enum class Format { Ascii, BinaryLE, BinaryBE };

struct Property {
  std::string name;
  int type = 0;        // byte size of the value (1, 2, 4, 8), negative for signed integers, 0 unused
  bool real = false;   // float or double
  bool list = false;
  int count_type = 0;  // the list count's size
  bool count_signed = false;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

// A scalar type name: byte size and kind.
bool scalar_type(const std::string& t, int& size, bool& real, bool& is_signed) {
  struct Entry {
    const char* name;
    int size;
    bool real, is_signed;
  };
  static const Entry kTypes[] = {{"char", 1, false, true},    {"int8", 1, false, true},    {"uchar", 1, false, false},
                                 {"uint8", 1, false, false},  {"short", 2, false, true},   {"int16", 2, false, true},
                                 {"ushort", 2, false, false}, {"uint16", 2, false, false}, {"int", 4, false, true},
                                 {"int32", 4, false, true},   {"uint", 4, false, false},   {"uint32", 4, false, false},
                                 {"float", 4, true, true},    {"float32", 4, true, true},  {"double", 8, true, true},
                                 {"float64", 8, true, true}};
  for (const Entry& e : kTypes) {
    if (t == e.name) {
      size = e.size;
      real = e.real;
      is_signed = e.is_signed;
      return true;
    }
  }
  return false;
}

// A mesh attribute made of one or three scalar properties of an element.
struct AttributeGroup {
  std::string name;
  std::vector<size_t> props;
};

// Mitsuba 3's grouping of a vertex or face element's other properties into attributes
// (src/shapes/ply.h, find_other_fields): r g b (or red green blue) make "<type>color" (an
// alpha is dropped); then each run of consecutive properties named prefix_X, whose one-letter
// postfixes follow x y z, r g b, 0 1 2 or 1 2 3 and number 1 or 3, makes "<type>prefix" (with
// "_color" appended for r g b). Runs that break these rules, repeated prefixes, lists and
// names without a postfix are skipped. `type` is "vertex_" or "face_".
std::vector<AttributeGroup> mesh_attribute_groups(const std::vector<Property>& props, const std::string& type,
                                                  std::set<std::string> reserved) {
  std::vector<AttributeGroup> out;
  auto find = [&](const char* n) {
    for (size_t k = 0; k < props.size(); ++k) {
      if (props[k].name == n && !props[k].list) return int(k);
    }
    return -1;
  };
  int r = find("r"), g = find("g"), b = find("b");
  if (r < 0 || g < 0 || b < 0) r = find("red"), g = find("green"), b = find("blue");
  if (r >= 0 && g >= 0 && b >= 0) out.push_back({type + "color", {size_t(r), size_t(g), size_t(b)}});
  for (const char* n : {"r", "g", "b", "a", "red", "green", "blue", "alpha"}) reserved.insert(n);
  static const char* const kPostfix[4] = {"xr01", "yg12", "zb23", "wa34"};
  auto prefix_of = [&](size_t k) {
    const std::string& n = props[k].name;
    const size_t us = n.find_last_of('_');
    if (props[k].list || reserved.count(n) || us == std::string::npos || us == 0 || us + 2 != n.size()) return std::string();
    return n.substr(0, us);
  };
  std::set<std::string> seen;
  for (size_t k = 0; k < props.size();) {
    const std::string prefix = prefix_of(k);
    if (prefix.empty()) {
      ++k;
      continue;
    }
    size_t end = k;
    while (end < props.size() && prefix_of(end) == prefix) ++end;
    const size_t n = end - k;
    const char* first = std::strchr(kPostfix[0], props[k].name.back());
    bool ok = !seen.count(prefix) && first && (n == 1 || n == 3);
    const size_t category = first ? size_t(first - kPostfix[0]) : 0;
    for (size_t i = 0; ok && i < n; ++i) ok = props[k + i].name.back() == kPostfix[i][category];
    if (ok) {
      seen.insert(prefix);  // as Mitsuba: only an accepted prefix blocks a later run of it
      AttributeGroup group{type + prefix + (category == 1 ? "_color" : ""), {}};
      for (size_t i = 0; i < n; ++i) group.props.push_back(k + i);
      out.push_back(group);
    }
    k = end;
  }
  return out;
}

// An attribute's value as Mitsuba's PLY reader converts it: floats as they are, integers
// normalised to [0, 1] ([-1, 1] when signed) and decoded from sRGB.
float attribute_value(const Property& p, double v) {
  if (p.real) return float(v);
  const int bits = 8 * std::abs(p.type);
  const double max = p.type < 0 ? std::ldexp(1.0, bits - 1) - 1.0 : std::ldexp(1.0, bits) - 1.0;
  const float x = float(std::max(-1.0, v / max));
  return x < 0.0f ? -srgb_to_linear(-x) : srgb_to_linear(x);
}

class Reader {
 public:
  Reader(const std::string& bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  MeshData read() {
    header();
    MeshData mesh;
    std::vector<Vec3> normals;
    std::vector<Vec2> uvs;
    bool have_vertices = false, have_faces = false;
    for (const Element& e : elements_) {
      if (e.name == "vertex") {
        if (have_vertices) fail("a second vertex element");
        have_vertices = true;
        vertices(e, mesh, normals, uvs);
      } else if (e.name == "face") {
        if (!have_vertices) fail("the face element comes before the vertex element");
        if (have_faces) fail("a second face element");
        have_faces = true;
        faces(e, mesh, normals, uvs);
      } else {
        for (uint64_t i = 0; i < e.count; ++i) {
          begin_row(e, i);
          for (const Property& p : e.props) skip(p);
          end_row(e, i);
        }
      }
    }
    if (!have_vertices) fail("no vertex element");
    if (mesh.tris.empty()) fail("no faces");
    return mesh;
  }

 private:
  const std::string& bytes_;
  const std::string& file_;
  Format format_ = Format::Ascii;
  std::vector<Element> elements_;
  size_t at_ = 0;     // read position
  size_t line_ = 1;   // ASCII: the line being read
  std::vector<std::string> tokens_;  // ASCII: the current line's tokens
  size_t token_ = 0;

  [[noreturn]] void fail(const std::string& m) const {
    if (format_ == Format::Ascii && line_ > 0) throw InputError(file_ + ":" + std::to_string(line_) + ": " + m);
    throw InputError(file_ + ": " + m);
  }

  // The next header line, without its end.
  std::string header_line() {
    const size_t end = bytes_.find('\n', at_);
    if (end == std::string::npos) fail("the header has no end_header line");
    std::string l = bytes_.substr(at_, end - at_);
    if (!l.empty() && l.back() == '\r') l.pop_back();
    at_ = end + 1;
    return l;
  }

  void header() {
    if (header_line() != "ply") fail("not a PLY file (it does not start with \"ply\")");
    ++line_;
    std::string format;
    for (;; ++line_) {
      if (line_ > 100000) fail("the header is longer than 100000 lines");
      std::istringstream in(header_line());
      std::string word;
      in >> word;
      if (word == "end_header") break;
      if (word.empty() || word == "comment" || word == "obj_info") continue;
      if (word == "format") {
        std::string version;
        in >> format >> version;
        if (format == "ascii") format_ = Format::Ascii;
        else if (format == "binary_little_endian") format_ = Format::BinaryLE;
        else if (format == "binary_big_endian") format_ = Format::BinaryBE;
        else fail("unknown format \"" + format + "\" (known: ascii, binary_little_endian, binary_big_endian)");
      } else if (word == "element") {
        Element e;
        std::string count;
        in >> e.name >> count;
        char* end = nullptr;
        const unsigned long long n = std::strtoull(count.c_str(), &end, 10);
        if (e.name.empty() || count.empty() || *end != '\0' || count[0] == '-' || n > (1ull << 31)) {
          fail("element line: expected \"element NAME COUNT\" with a count up to 2^31");
        }
        e.count = n;
        elements_.push_back(e);
      } else if (word == "property") {
        if (elements_.empty()) fail("a property before any element");
        Property p;
        std::string type;
        in >> type;
        int size = 0;
        bool is_signed = false;
        if (type == "list") {
          std::string count_type, item_type;
          in >> count_type >> item_type >> p.name;
          bool count_real = false;
          if (!scalar_type(count_type, p.count_type, count_real, p.count_signed) || count_real) {
            fail("a list's count type must be an integer type, not \"" + count_type + "\"");
          }
          if (!scalar_type(item_type, size, p.real, is_signed)) fail("unknown type \"" + item_type + "\"");
          p.list = true;
        } else {
          in >> p.name;
          if (!scalar_type(type, size, p.real, is_signed)) fail("unknown type \"" + type + "\"");
        }
        if (p.name.empty()) fail("a property without a name");
        p.type = is_signed && !p.real ? -size : size;
        elements_.back().props.push_back(p);
      } else {
        fail("unexpected header line \"" + word + "\"");
      }
    }
    if (format.empty()) fail("the header has no format line");
    ++line_;
  }

  // ---- reading values, ASCII or binary
  void begin_row(const Element& e, uint64_t i) {
    if (format_ != Format::Ascii) return;
    // One element per line; blank lines are skipped.
    for (;;) {
      if (at_ >= bytes_.size()) fail("the file ends before " + e.name + " " + std::to_string(i) + " (truncated)");
      size_t end = bytes_.find('\n', at_);
      if (end == std::string::npos) end = bytes_.size();
      std::istringstream in(bytes_.substr(at_, end - at_));
      at_ = end + 1;
      tokens_.clear();
      token_ = 0;
      std::string t;
      while (in >> t) tokens_.push_back(t);
      if (!tokens_.empty()) return;
      ++line_;
    }
  }
  void end_row(const Element& e, uint64_t i) {
    if (format_ != Format::Ascii) return;
    if (token_ != tokens_.size()) fail(e.name + " " + std::to_string(i) + " has more values than its properties");
    ++line_;
  }

  double ascii_value(bool real) {
    if (token_ >= tokens_.size()) fail("a line has fewer values than its element's properties");
    const std::string& t = tokens_[token_++];
    char* end = nullptr;
    const double v = real ? std::strtod(t.c_str(), &end) : double(std::strtoll(t.c_str(), &end, 10));
    if (end != t.c_str() + t.size()) fail("\"" + t + "\" is not a number");
    return v;
  }

  double binary_value(int type, bool real) {
    const int size = std::abs(type);
    if (bytes_.size() - at_ < size_t(size)) fail("the file ends in the middle of the data (truncated)");
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + at_, size_t(size));
    at_ += size_t(size);
    if (format_ == Format::BinaryBE) std::reverse(b, b + size);
    if (real) {
      if (size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    uint64_t u = 0;
    std::memcpy(&u, b, size_t(size));  // little-endian host
    if (type < 0 && size < 8 && (u >> (size * 8 - 1)) & 1) return double(int64_t(u | (~uint64_t(0) << (size * 8))));
    return double(u);
  }

  double value(int type, bool real) { return format_ == Format::Ascii ? ascii_value(real) : binary_value(type, real); }

  uint64_t list_count(const Property& p) {
    const double n = value(p.count_signed ? -p.count_type : p.count_type, false);
    if (!(n >= 0.0) || n > 1e6) fail("a list of " + std::to_string(n) + " items (0 to 10^6 allowed)");
    return uint64_t(n);
  }

  void skip(const Property& p) {
    if (!p.list) {
      value(p.type, p.real);
      return;
    }
    const uint64_t n = list_count(p);
    for (uint64_t k = 0; k < n; ++k) value(p.type, p.real);
  }

  // Binary: the bytes left must hold at least `count` rows of the fixed-size part of `e`.
  void check_room(const Element& e) {
    if (format_ == Format::Ascii) return;
    uint64_t row = 0;
    for (const Property& p : e.props) row += uint64_t(p.list ? p.count_type : std::abs(p.type));
    if (row > 0 && e.count > (bytes_.size() - at_) / row) {
      fail("the file is too short for its " + std::to_string(e.count) + " " + e.name + " elements (truncated)");
    }
  }

  void vertices(const Element& e, MeshData& mesh, std::vector<Vec3>& normals, std::vector<Vec2>& uvs) {
    int ix[3] = {-1, -1, -1}, in[3] = {-1, -1, -1}, iuv[2] = {-1, -1};
    static const char* const kU[] = {"u", "s", "texture_u", "texture_s"};
    static const char* const kV[] = {"v", "t", "texture_v", "texture_t"};
    for (size_t k = 0; k < e.props.size(); ++k) {
      const std::string& n = e.props[k].name;
      for (int c = 0; c < 3; ++c) {
        if (n == std::string(1, char('x' + c))) ix[c] = int(k);
        if (n == "n" + std::string(1, char('x' + c))) in[c] = int(k);
      }
      for (int c = 0; c < 4; ++c) {
        if (n == kU[c] && iuv[0] < 0) iuv[0] = int(k);
        if (n == kV[c] && iuv[1] < 0) iuv[1] = int(k);
      }
      if (e.props[k].list && (n == "x" || n == "y" || n == "z")) fail("vertex property " + n + " is a list");
    }
    if (ix[0] < 0 || ix[1] < 0 || ix[2] < 0) fail("the vertex element lacks x, y or z");
    vertex_groups_ = mesh_attribute_groups(e.props, "vertex_", {"x", "y", "z", "nx", "ny", "nz", "u", "v", "s", "t"});
    vertex_values_.assign(vertex_groups_.size(), {});
    const bool has_n = in[0] >= 0 && in[1] >= 0 && in[2] >= 0, has_uv = iuv[0] >= 0 && iuv[1] >= 0;
    check_room(e);
    // An ASCII vertex takes at least 6 bytes ("0 0 0\n"): no more can be in the file.
    mesh.verts.reserve(std::min<uint64_t>(e.count, bytes_.size() / 6 + 1));
    std::vector<double> row(e.props.size());
    for (uint64_t i = 0; i < e.count; ++i) {
      begin_row(e, i);
      for (size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        if (p.list) skip(p);
        else row[k] = value(p.type, p.real);
      }
      attribute_row(e, i, vertex_groups_, row, vertex_values_);
      end_row(e, i);
      const Vec3 v{float(row[size_t(ix[0])]), float(row[size_t(ix[1])]), float(row[size_t(ix[2])])};
      if (!is_finite(v)) fail("vertex " + std::to_string(i) + " is not finite");
      mesh.verts.push_back(v);
      if (has_n) normals.emplace_back(float(row[size_t(in[0])]), float(row[size_t(in[1])]), float(row[size_t(in[2])]));
      if (has_uv) uvs.emplace_back(float(row[size_t(iuv[0])]), float(row[size_t(iuv[1])]));
    }
  }

  // Appends a row's values of each attribute group; non-finite values are an error.
  void attribute_row(const Element& e, uint64_t i, const std::vector<AttributeGroup>& groups,
                     const std::vector<double>& row, std::vector<std::vector<float>>& values) {
    for (size_t g = 0; g < groups.size(); ++g) {
      for (size_t k : groups[g].props) {
        const float v = attribute_value(e.props[k], row[k]);
        if (!std::isfinite(v)) fail(e.name + " " + std::to_string(i) + ": property " + e.props[k].name + " is not finite");
        values[g].push_back(v);
      }
    }
  }

  std::vector<AttributeGroup> vertex_groups_;
  std::vector<std::vector<float>> vertex_values_;  // per group, its values vertex by vertex

  void faces(const Element& e, MeshData& mesh, const std::vector<Vec3>& normals, const std::vector<Vec2>& uvs) {
    int list = -1;
    for (size_t k = 0; k < e.props.size(); ++k) {
      const Property& p = e.props[k];
      if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) list = int(k);
    }
    if (list < 0) fail("the face element has no vertex_indices list");
    if (e.props[size_t(list)].real) fail("vertex_indices must be integers");
    check_room(e);
    const uint64_t nv = mesh.verts.size();
    const std::vector<AttributeGroup> groups =
        mesh_attribute_groups(e.props, "face_", {e.props[size_t(list)].name});
    std::vector<std::vector<float>> face_values(groups.size()), values(groups.size());
    std::vector<double> row(e.props.size());
    std::vector<int> poly;
    for (uint64_t i = 0; i < e.count; ++i) {
      begin_row(e, i);
      const size_t first_triangle = mesh.tris.size();
      for (size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        if (int(k) != list) {
          if (p.list) skip(p);
          else row[k] = value(p.type, p.real);
          continue;
        }
        const uint64_t n = list_count(p);
        if (n < 3) fail("face " + std::to_string(i) + " has " + std::to_string(n) + " vertices (3 or more needed)");
        poly.clear();
        for (uint64_t c = 0; c < n; ++c) {
          const double v = value(p.type, false);
          if (!(v >= 0.0) || v >= double(nv)) fail("face " + std::to_string(i) + " has a vertex index out of range");
          poly.push_back(int(v));
        }
        for (size_t c = 1; c + 1 < poly.size(); ++c) mesh.tris.emplace_back(poly[0], poly[c], poly[c + 1]);
      }
      for (auto& v : values) v.clear();
      attribute_row(e, i, groups, row, values);
      end_row(e, i);
      // Each triangle of the face's fan gets the face's values.
      for (size_t t = first_triangle; t < mesh.tris.size(); ++t) {
        for (size_t g = 0; g < groups.size(); ++g) face_values[g].insert(face_values[g].end(), values[g].begin(), values[g].end());
      }
    }
    set_vertex_attributes(mesh, normals, uvs);
    for (size_t g = 0; g < vertex_groups_.size(); ++g) {
      add_mesh_attribute(mesh, vertex_groups_[g].name, int(vertex_groups_[g].props.size()), false, vertex_values_[g]);
    }
    for (size_t g = 0; g < groups.size(); ++g) {
      add_mesh_attribute(mesh, groups[g].name, int(groups[g].props.size()), true, face_values[g]);
    }
  }
};

}  // namespace

MeshData parse_ply(const std::string& bytes, const std::string& name) { return Reader(bytes, name).read(); }

MeshData read_ply(const std::string& path) {
  return parse_ply(read_file_bytes(path, "mesh file"), path);
}

}  // namespace caustica
