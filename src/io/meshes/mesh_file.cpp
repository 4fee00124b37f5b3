// Dispatch by extension and the checks every reader shares.
#include "io/meshes/mesh_file.h"
#include <algorithm>
#include <cmath>
#include <filesystem>
#include "core/error.h"

namespace caustica {

void set_vertex_attributes(MeshData& mesh, const std::vector<Vec3>& normals, const std::vector<Vec2>& uvs) {
  mesh.attributes.clear();
  if (normals.empty() && uvs.empty()) return;
  for (const glm::ivec3& t : mesh.tris) {
    TriangleAttributes a;
    a.has_normals = !normals.empty();
    a.has_uvs = !uvs.empty();
    for (int k = 0; k < 3; ++k) {
      if (a.has_normals) a.n[k] = normals[size_t(t[k])];
      if (a.has_uvs) a.uv[k] = uvs[size_t(t[k])];
    }
    a.has_normals = a.has_normals && is_finite(a.n[0]) && is_finite(a.n[1]) && is_finite(a.n[2]);
    a.has_uvs = a.has_uvs && std::isfinite(a.uv[0].x + a.uv[0].y + a.uv[1].x + a.uv[1].y + a.uv[2].x + a.uv[2].y);
    mesh.attributes.push_back(a);
  }
}

void add_mesh_attribute(MeshData& mesh, const std::string& name, int channels, bool per_face,
                        const std::vector<float>& values) {
  MeshAttribute a;
  a.name = name;
  a.channels = channels == 1 ? 1 : 3;
  a.per_face = per_face;
  const size_t stride = size_t(channels);
  auto value = [&](size_t i) {
    const float* v = &values[i * stride];
    return channels == 1 ? Color(v[0]) : Color(v[0], v[1], v[2]);
  };
  a.values.reserve(mesh.tris.size() * (per_face ? 1 : 3));
  for (size_t t = 0; t < mesh.tris.size(); ++t) {
    if (per_face) a.values.push_back(value(t));
    else for (int k = 0; k < 3; ++k) a.values.push_back(value(size_t(mesh.tris[t][k])));
  }
  mesh.extra.list.push_back(std::move(a));
}

void add_smooth_normals(MeshData& mesh) {
  std::vector<Vec3> sum(mesh.verts.size(), Vec3(0.0f));
  for (const glm::ivec3& t : mesh.tris) {
    const Vec3 n = glm::cross(mesh.verts[size_t(t[1])] - mesh.verts[size_t(t[0])], mesh.verts[size_t(t[2])] - mesh.verts[size_t(t[0])]);
    if (!is_finite(n)) continue;
    for (int k = 0; k < 3; ++k) sum[size_t(t[k])] += n;
  }
  if (mesh.attributes.empty()) mesh.attributes.resize(mesh.tris.size());
  for (size_t i = 0; i < mesh.tris.size(); ++i) {
    TriangleAttributes& a = mesh.attributes[i];
    if (a.has_normals) continue;
    bool ok = true;
    Vec3 n[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = sum[size_t(mesh.tris[i][k])];
      const float len = glm::length(v);
      ok = ok && len > 0.0f && std::isfinite(len);
      n[k] = ok ? v / len : Vec3(0.0f);
    }
    if (!ok) continue;
    for (int k = 0; k < 3; ++k) a.n[k] = n[k];
    a.has_normals = true;
  }
}

void rebuild_normals_with_creases(MeshData& mesh, double max_degrees) {
  const size_t nt = mesh.tris.size();
  std::vector<Vec3> face(nt, Vec3(0.0f));  // area-weighted (twice the area)
  std::vector<std::vector<uint32_t>> around(mesh.verts.size());
  for (size_t i = 0; i < nt; ++i) {
    const glm::ivec3& t = mesh.tris[i];
    const Vec3 n = glm::cross(mesh.verts[size_t(t[1])] - mesh.verts[size_t(t[0])], mesh.verts[size_t(t[2])] - mesh.verts[size_t(t[0])]);
    if (is_finite(n)) face[i] = n;
    for (int k = 0; k < 3; ++k) around[size_t(t[k])].push_back(uint32_t(i));
  }
  const float cos_max = float(std::cos(max_degrees * 3.14159265358979323846 / 180.0));
  mesh.attributes.resize(nt);
  for (size_t i = 0; i < nt; ++i) {
    TriangleAttributes& a = mesh.attributes[i];
    a.has_normals = false;
    const float len_i = glm::length(face[i]);
    if (!(len_i > 0.0f) || !std::isfinite(len_i)) continue;
    const Vec3 ni = face[i] / len_i;
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k) {
      Vec3 sum(0.0f);
      for (uint32_t f : around[size_t(mesh.tris[i][k])]) {
        const float len = glm::length(face[f]);
        if (len > 0.0f && glm::dot(face[f] / len, ni) >= cos_max) sum += face[f];
      }
      const float len = glm::length(sum);
      ok = len > 0.0f && std::isfinite(len);
      a.n[k] = ok ? sum / len : Vec3(0.0f);
    }
    a.has_normals = ok;
  }
}

MeshData read_mesh_file(const std::string& path, int shape_index) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError("mesh file not found: tried " + path);
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError("mesh path is not a regular file: " + path);
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".serialized" && shape_index != 0) throw InputError(path + ": shape_index applies to .serialized files only");
  if (ext == ".obj") return read_obj(path);
  if (ext == ".serialized") return read_serialized(path, shape_index);
  if (ext == ".ply") return read_ply(path);
  throw InputError(path + ": unknown mesh format \"" + ext + "\" (known: .obj, .ply, .serialized)");
}

}  // namespace caustica
