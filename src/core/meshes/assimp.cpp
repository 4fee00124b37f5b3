// PLY, glTF and FBX meshes through Assimp (Debian's libassimp-dev): ASCII and binary PLY with
// normals and UVs. Assimp's post-processing triangulates; node transforms are applied.
#include <cmath>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include "core/json_reader.h"
#include "core/meshes/mesh_file.h"

namespace caustica {
namespace {

void add_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, const std::string& file, MeshData& out,
              bool& any_attributes) {
  const aiMatrix4x4 m = parent * node.mTransformation;
  aiMatrix3x3 nm(m);
  nm.Inverse().Transpose();
  for (unsigned mi = 0; mi < node.mNumMeshes; ++mi) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[mi]];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const size_t base = out.verts.size();
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = m * mesh.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw InputError(file + ": vertex " + std::to_string(v) + " of mesh " + std::to_string(node.mMeshes[mi]) +
                         " is not finite");
      }
      out.verts.emplace_back(p.x, p.y, p.z);
    }
    const bool normals = mesh.HasNormals(), uvs = mesh.HasTextureCoords(0);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      glm::ivec3 t;
      TriangleAttributes a;
      a.has_normals = normals;
      a.has_uvs = uvs;
      for (int k = 0; k < 3; ++k) {
        const unsigned i = face.mIndices[k];
        if (i >= mesh.mNumVertices) throw InputError(file + ": face " + std::to_string(f) + " has a vertex index out of range");
        t[k] = int(base + i);
        if (normals) {
          const aiVector3D n = nm * mesh.mNormals[i];
          a.n[k] = Vec3(n.x, n.y, n.z);
          a.has_normals = a.has_normals && is_finite(a.n[k]);
        }
        if (uvs) {
          const aiVector3D& uv = mesh.mTextureCoords[0][i];
          a.uv[k] = Vec2(uv.x, uv.y);
          a.has_uvs = a.has_uvs && std::isfinite(uv.x) && std::isfinite(uv.y);
        }
      }
      out.tris.push_back(t);
      out.attributes.push_back(a);
      any_attributes = any_attributes || a.has_normals || a.has_uvs;
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) add_node(scene, *node.mChildren[c], m, file, out, any_attributes);
}

}  // namespace

MeshData read_assimp(const std::string& file) {
  Assimp::Importer importer;
  // Points and lines are dropped; nothing else is changed (no vertex joining, no generated normals).
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(file, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    throw InputError("cannot read mesh file " + file + ": " + importer.GetErrorString());
  }
  MeshData out;
  bool any_attributes = false;
  add_node(*scene, *scene->mRootNode, aiMatrix4x4(), file, out, any_attributes);
  if (!any_attributes) out.attributes.clear();
  if (out.tris.empty()) throw InputError("mesh file " + file + " has no triangles");
  return out;
}

}  // namespace caustica
