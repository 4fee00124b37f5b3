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
