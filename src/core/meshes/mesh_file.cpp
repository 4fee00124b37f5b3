// Dispatch by extension and the checks every reader shares.
#include "core/meshes/mesh_file.h"
#include <algorithm>
#include <filesystem>
#include "core/json_reader.h"

namespace caustica {

MeshData read_mesh_file(const std::string& path, int shape_index) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError("mesh file not found: tried " + path);
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError("mesh path is not a regular file: " + path);
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".serialized" && shape_index != 0) throw InputError(path + ": shape_index applies to .serialized files only");
  if (ext == ".obj") return read_obj(path);
  if (ext == ".serialized") return read_serialized(path, shape_index);
  if (ext == ".ply" || ext == ".gltf" || ext == ".glb" || ext == ".fbx") return read_assimp(path);
  throw InputError(path + ": unknown mesh format \"" + ext + "\" (known: .obj, .ply, .serialized, .gltf, .glb, .fbx)");
}

}  // namespace caustica
