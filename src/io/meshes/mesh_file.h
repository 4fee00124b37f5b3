// Triangle meshes read from files: OBJ (tinyobjloader), PLY (our reader: ply.cpp says why) and
// Mitsuba's .serialized. Every reader checks what it reads: a non-finite number, an index out
// of range or a truncated file is an InputError naming the file and the line or element.
#pragma once
#include <string>
#include <vector>
#include "core/shape.h"

namespace caustica {

// A material a mesh file brings along (OBJ's .mtl), in the terms of our materials.
struct MeshMaterial {
  std::string name;
  Color kd{0.0f}, ks{0.0f}, ke{0.0f}, tf{0.0f};
  float ns = 0.0f, ni = 1.0f, d = 1.0f;
  int illum = -1;
  std::string map_kd;  // path of the diffuse texture, relative to the mesh file's folder
};

struct MeshData {
  std::vector<Vec3> verts;
  std::vector<glm::ivec3> tris;
  std::vector<TriangleAttributes> attributes;  // empty, or one per triangle
  // Per triangle, an index into `materials` or -1 (only when the file names materials).
  std::vector<int> material_ids;
  std::vector<MeshMaterial> materials;
  std::string material_dir;  // the folder map_kd paths are relative to
  // Per-vertex and per-face values besides these (PLY properties, .serialized colours), per
  // triangle; the scene keeps them and points the triangles' attributes at them.
  MeshAttributes extra;
};

// Per-triangle shading data from per-vertex normals and UVs (either may be empty, or one per
// vertex); a triangle with a non-finite normal or UV goes without it.
void set_vertex_attributes(MeshData& mesh, const std::vector<Vec3>& normals, const std::vector<Vec2>& uvs);

// Adds a mesh attribute from `channels` (1, 3 or 4: alpha dropped) values per vertex, or per
// triangle with `per_face`. The values must be finite.
void add_mesh_attribute(MeshData& mesh, const std::string& name, int channels, bool per_face,
                        const std::vector<float>& values);

// Area-weighted vertex normals for the triangles that have none (as Mitsuba does for a mesh
// without normals, unless face_normals); a vertex whose normals cancel leaves its triangles flat.
void add_smooth_normals(MeshData& mesh);

// Mitsuba 0.6's maxSmoothAngle: every triangle's normals rebuilt (the file's dropped), each
// corner's the area-weighted mean of the faces around its vertex whose normals lie within
// `max_degrees` of this face's, so that creases sharper than that stay sharp.
void rebuild_normals_with_creases(MeshData& mesh, double max_degrees);

// Reads by the extension (.obj, .ply, .serialized).
// `shape_index` picks one shape of a .serialized file holding several.
MeshData read_mesh_file(const std::string& path, int shape_index = 0);

// The readers, for tests and fuzzing.
MeshData read_obj(const std::string& path);
MeshData read_ply(const std::string& path);
MeshData parse_ply(const std::string& bytes, const std::string& name);
MeshData read_serialized(const std::string& path, int shape_index);
// Parses .serialized data held in memory; `name` names it in messages.
MeshData parse_serialized(const std::string& bytes, const std::string& name, int shape_index);

}  // namespace caustica
