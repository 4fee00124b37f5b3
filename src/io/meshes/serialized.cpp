// Mitsuba's .serialized meshes: per shape a little-endian header (uint16 0x041C, uint16 version
// 3 or 4) and a zlib stream holding flags, (v4) a name, counts, positions, normals, UVs, colours
// and indices. A table of shape offsets closes the file.
#include <cmath>
#include <cstring>
#include <limits>
#include <zlib.h>
#include "io/file_bytes.h"
#include "core/error.h"
#include "core/memory.h"
#include "core/shape.h"
#include "io/meshes/mesh_file.h"

namespace caustica {
namespace {

constexpr uint16_t kMagic = 0x041C;
constexpr size_t kMaxNameLength = size_t(1) << 16;  // a v4 shape's name, its terminating zero included
enum : uint32_t {
  kVertexNormals = 0x0001,
  kTexcoords = 0x0002,
  kColors = 0x0008,
  kFaceNormals = 0x0010,
  kSinglePrecision = 0x1000,
  kDoublePrecision = 0x2000,
};

template <class T>
T load(const std::string& bytes, size_t at) {
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof(T));
  return v;
}

// The zlib stream of one shape, inflated on demand: the header first, then as much as its counts
// declare and memory allows, so that a small file cannot inflate into gigabytes unasked.
class Inflater {
 public:
  Inflater(const std::string& bytes, size_t at, const std::string& name) : at_(at), name_(name) {
    if (inflateInit(&zs_) != Z_OK) throw InputError(name + ": zlib cannot be initialised");
    zs_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + at));
    zs_.avail_in = uInt(std::min<size_t>(bytes.size() - at, std::numeric_limits<uInt>::max()));
  }
  ~Inflater() { inflateEnd(&zs_); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  // Appends to `out` until it holds `size` bytes or the stream ends.
  void fill(std::string& out, size_t size) {
    char buffer[1 << 16];
    while (!ended_ && out.size() < size) {
      zs_.next_out = reinterpret_cast<Bytef*>(buffer);
      zs_.avail_out = uInt(std::min(sizeof(buffer), size - out.size()));
      const uInt asked = zs_.avail_out;
      const int rc = inflate(&zs_, Z_NO_FLUSH);
      out.append(buffer, asked - zs_.avail_out);
      if (rc == Z_STREAM_END) {
        ended_ = true;
      } else if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT || rc == Z_MEM_ERROR ||
                 (rc == Z_BUF_ERROR && zs_.avail_in == 0)) {
        throw InputError(name_ + ": the compressed mesh data at byte " + std::to_string(at_) +
                         (rc == Z_BUF_ERROR ? " is truncated" : " is corrupt"));
      }
    }
  }

 private:
  z_stream zs_{};
  size_t at_;
  const std::string& name_;
  bool ended_ = false;
};

// Reads the uncompressed stream of one shape.
class StreamReader {
 public:
  StreamReader(const std::string& data, const std::string& name) : data_(data), name_(name) {}
  template <class T>
  T get(const char* what) {
    need(sizeof(T), what);
    const T v = load<T>(data_, at_);
    at_ += sizeof(T);
    return v;
  }
  void need(size_t n, const char* what) const {
    if (n > data_.size() - at_) throw InputError(name_ + ": truncated while reading the " + what);
  }
  std::string cstring() {
    const size_t end = data_.find('\0', at_);
    if (end == std::string::npos) throw InputError(name_ + ": truncated while reading the shape name");
    std::string s = data_.substr(at_, end - at_);
    at_ = end + 1;
    return s;
  }
  // n vectors of `dim` reals (float or double).
  void reals(size_t n, int dim, bool dbl, float* out, const char* what) {
    const size_t size = dbl ? 8 : 4;
    if (n > (data_.size() - at_) / (size * size_t(dim))) throw InputError(name_ + ": truncated while reading the " + what);
    for (size_t i = 0; i < n * size_t(dim); ++i) {
      out[i] = dbl ? float(load<double>(data_, at_ + 8 * i)) : load<float>(data_, at_ + 4 * i);
    }
    at_ += n * size_t(dim) * size;
  }
  size_t position() const { return at_; }

 private:
  const std::string& data_;
  const std::string& name_;
  size_t at_ = 0;
};

}  // namespace

MeshData parse_serialized(const std::string& bytes, const std::string& name, int shape_index) {
  if (bytes.size() < 4 || load<uint16_t>(bytes, 0) != kMagic) {
    throw InputError(name + ": not a Mitsuba .serialized mesh (the file does not start with 0x041C)");
  }
  const uint16_t version = load<uint16_t>(bytes, 2);
  if (version != 3 && version != 4) throw InputError(name + ": unsupported .serialized version " + std::to_string(version) + " (known: 3, 4)");
  size_t offset = 0;
  if (shape_index < 0) throw InputError(name + ": shape_index must not be negative");
  if (shape_index > 0) {
    // The closing table: one offset per shape (uint64 in v4, uint32 in v3), then the count.
    if (bytes.size() < 8) throw InputError(name + ": truncated (no table of shapes)");
    const uint32_t count = load<uint32_t>(bytes, bytes.size() - 4);
    const size_t entry = version == 4 ? 8 : 4;
    if (uint64_t(count) * entry + 4 > bytes.size()) throw InputError(name + ": the table of shapes is corrupt");
    if (uint32_t(shape_index) >= count) {
      throw InputError(name + ": shape_index " + std::to_string(shape_index) + " is out of range (the file holds " +
                       std::to_string(count) + " shapes)");
    }
    const size_t table = bytes.size() - 4 - size_t(count) * entry;
    offset = version == 4 ? size_t(load<uint64_t>(bytes, table + entry * size_t(shape_index)))
                          : size_t(load<uint32_t>(bytes, table + entry * size_t(shape_index)));
    if (offset > table || table - offset < 4 || load<uint16_t>(bytes, offset) != kMagic) {
      throw InputError(name + ": the offset of shape " + std::to_string(shape_index) + " does not point at a shape");
    }
  }
  Inflater zlib(bytes, offset + 4, name);
  std::string data;
  zlib.fill(data, 4 + kMaxNameLength + 16);  // flags, (v4) the name, the counts
  StreamReader in(data, name);
  const uint32_t flags = in.get<uint32_t>("flags");
  if (version == 4) in.cstring();
  const uint64_t nv = in.get<uint64_t>("vertex count"), nt = in.get<uint64_t>("triangle count");
  const bool dbl = (flags & kDoublePrecision) != 0;
  if (nv == 0 || nt == 0) throw InputError(name + ": shape " + std::to_string(shape_index) + " has no triangles");
  if (nv > (uint64_t(1) << 31) || nt > (uint64_t(1) << 31)) throw InputError(name + ": more than 2^31 vertices or triangles");
  // What the counts declare: the stream's bytes, then our arrays (positions, normals, UVs and
  // indices; per triangle its attributes and a material id).
  const size_t real = dbl ? 8 : 4;
  const int per_vertex = 3 + ((flags & kVertexNormals) ? 3 : 0) + ((flags & kTexcoords) ? 2 : 0) + ((flags & kColors) ? 3 : 0);
  const double stream_bytes = double(in.position()) + double(nv) * per_vertex * real + double(nt) * 12.0;
  // The first 64 MiB unchecked: a file that declares more than it holds is then "truncated".
  // Past them, the whole is checked first: the stream, our arrays, and per triangle what the
  // scene makes of it (a primitive, its attributes, its share of the BVH).
  constexpr size_t kUnchecked = size_t(64) << 20;
  data.reserve(std::min(size_t(stream_bytes), kUnchecked));
  zlib.fill(data, std::min(size_t(stream_bytes), kUnchecked));
  if (data.size() < size_t(stream_bytes) && data.size() >= kUnchecked) {
    const double per_triangle = 12.0 + 4.0 + 2.0 * sizeof(TriangleAttributes) + sizeof(Primitive) + 64.0;
    check_memory(stream_bytes + double(nv) * (12.0 + 4.0 * per_vertex) + double(nt) * per_triangle,
                 name + " (" + std::to_string(nv) + " vertices, " + std::to_string(nt) + " triangles)");
    data.reserve(size_t(stream_bytes));
    zlib.fill(data, size_t(stream_bytes));
  }
  // The stream must hold the positions and indices it declares before anything is allocated.
  in.need(size_t(nv) * 3 * real, "vertex positions");
  if (nt > (data.size() / 12)) throw InputError(name + ": truncated while reading the triangle indices");
  MeshData mesh;
  std::vector<float> pos(3 * nv), normals, uvs;
  in.reals(nv, 3, dbl, pos.data(), "vertex positions");
  for (size_t i = 0; i < nv; ++i) {
    mesh.verts.emplace_back(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    if (!is_finite(mesh.verts.back())) throw InputError(name + ": vertex " + std::to_string(i) + " is not finite");
  }
  if (flags & kVertexNormals) {
    normals.resize(3 * nv);
    in.reals(nv, 3, dbl, normals.data(), "vertex normals");
  }
  if (flags & kTexcoords) {
    uvs.resize(2 * nv);
    in.reals(nv, 2, dbl, uvs.data(), "texture coordinates");
  }
  std::vector<float> colours;
  if (flags & kColors) {
    colours.resize(3 * nv);
    in.reals(nv, 3, dbl, colours.data(), "vertex colours");
    for (size_t i = 0; i < colours.size(); ++i) {
      if (!std::isfinite(colours[i])) throw InputError(name + ": the colour of vertex " + std::to_string(i / 3) + " is not finite");
    }
  }
  for (size_t t = 0; t < nt; ++t) {
    glm::ivec3 tri;
    for (int k = 0; k < 3; ++k) {
      // Always uint32, as Mitsuba's own readers do (vertex counts above 2^31 are refused above).
      const uint64_t i = in.get<uint32_t>("triangle indices");
      if (i >= nv) throw InputError(name + ": triangle " + std::to_string(t) + " has a vertex index out of range");
      tri[k] = int(i);
    }
    mesh.tris.push_back(tri);
  }
  std::vector<Vec3> n;
  std::vector<Vec2> uv;
  if (!(flags & kFaceNormals)) {
    for (size_t i = 0; i < normals.size(); i += 3) n.emplace_back(normals[i], normals[i + 1], normals[i + 2]);
  }
  for (size_t i = 0; i < uvs.size(); i += 2) uv.emplace_back(uvs[i], uvs[i + 1]);
  set_vertex_attributes(mesh, n, uv);
  // Mitsuba 3 names them so for its mesh_attribute texture.
  if (!colours.empty()) add_mesh_attribute(mesh, "vertex_color", 3, false, colours);
  return mesh;
}

MeshData read_serialized(const std::string& path, int shape_index) {
  return parse_serialized(read_file_bytes(path, "mesh file"), path, shape_index);
}

}  // namespace caustica
