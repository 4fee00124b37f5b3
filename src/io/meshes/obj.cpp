// OBJ meshes through tinyobjloader, with a pass of our own that checks every number.
#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tiny_obj_loader.h>
#include "core/error.h"
#include "io/meshes/mesh_file.h"

namespace caustica {
namespace {

// tinyobjloader reads "nan", "inf" and garbage in v/vn/vt lines as 0 without a word, and 1e39
// as a float's infinity: every number there must be finite as a float, else the error names
// the file and the line. An mtllib must be
// a regular file (a FIFO or /dev/zero would block the reader or never end).
void check_obj_numbers(std::istream& in, const std::string& file) {
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    if (line.compare(0, 7, "mtllib ") == 0) {
      std::istringstream names(line.substr(7));
      std::string name;
      while (names >> name) {
        const std::filesystem::path mtl = std::filesystem::path(file).parent_path() / name;
        std::error_code ec;
        if (std::filesystem::exists(mtl, ec) && !std::filesystem::is_regular_file(mtl, ec)) {
          throw InputError(file + ":" + std::to_string(number) + ": mtllib " + name + " is not a regular file");
        }
      }
      continue;
    }
    if (line.size() < 2 || line[0] != 'v' || !(line[1] == ' ' || line[1] == '\t' || line[1] == 'n' || line[1] == 't')) continue;
    std::istringstream tokens(line.substr(line[1] == ' ' || line[1] == '\t' ? 1 : 2));
    std::string tok;
    while (tokens >> tok) {
      char* end = nullptr;
      const double v = std::strtod(tok.c_str(), &end);
      if (end == tok.c_str() || *end != '\0' || !std::isfinite(v)) {
        throw InputError(file + ":" + std::to_string(number) + ": \"" + tok + "\" is not a finite number");
      }
      if (!(std::abs(v) <= double(std::numeric_limits<float>::max()))) {
        throw InputError(file + ":" + std::to_string(number) + ": " + tok + " is too large for a float (the largest is about 3.4e38)");
      }
    }
  }
}

// A face corner's vn or vt index: -1 (none given) or one of the file's `count`.
void check_attribute_index(int index, size_t count, const char* what, const std::string& file, size_t face,
                           const std::string& shape) {
  if (index == -1 || (index >= 0 && size_t(index) < count)) return;
  throw InputError("OBJ file " + file + ": face " + std::to_string(face + 1) +
                   (shape.empty() ? std::string() : " of \"" + shape + "\"") + " names " + what + " " +
                   std::to_string(int64_t(index) + 1) + ", but the file has " + std::to_string(count));
}

Color rgb(const tinyobj::real_t* c) { return Color(c[0], c[1], c[2]); }

}  // namespace

MeshData read_obj(const std::string& file) {
  const std::filesystem::path path(file);
  std::ifstream probe(path);
  if (!probe) throw InputError("mesh file cannot be read: " + file);
  check_obj_numbers(probe, file);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = path.parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(file, config)) throw InputError("cannot parse OBJ file " + file + ": " + reader.Error());
  MeshData mesh;
  const auto& attrib = reader.GetAttrib();
  for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3) {
    mesh.verts.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
  }
  for (const auto& m : reader.GetMaterials()) {
    MeshMaterial mm;
    mm.name = m.name;
    mm.kd = rgb(m.diffuse);
    mm.ks = rgb(m.specular);
    mm.ke = rgb(m.emission);
    mm.tf = rgb(m.transmittance);
    mm.ns = float(m.shininess);
    mm.ni = float(m.ior);
    mm.d = float(m.dissolve);
    mm.illum = m.illum;
    mm.map_kd = m.diffuse_texname;
    for (const Color& c : {mm.kd, mm.ks, mm.ke, mm.tf}) {
      if (!is_finite(c) || c.x < 0 || c.y < 0 || c.z < 0) {
        throw InputError(file + ": material \"" + m.name + "\" has a negative or non-finite colour");
      }
    }
    if (!std::isfinite(mm.ns) || !std::isfinite(mm.ni) || !std::isfinite(mm.d)) {
      throw InputError(file + ": material \"" + m.name + "\" has a non-finite Ns, Ni or d");
    }
    mesh.materials.push_back(mm);
  }
  mesh.material_dir = path.parent_path().string();
  const size_t n_normals = attrib.normals.size() / 3, n_uvs = attrib.texcoords.size() / 2;
  bool any_attributes = false, any_material = false;
  for (const auto& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    for (size_t i = 0; i + 2 < idx.size(); i += 3) {
      glm::ivec3 t(idx[i].vertex_index, idx[i + 1].vertex_index, idx[i + 2].vertex_index);
      for (int k = 0; k < 3; ++k) {
        if (t[k] < 0 || size_t(t[k]) >= mesh.verts.size()) {
          throw InputError("OBJ file " + file + " has a face with a vertex index out of range");
        }
      }
      mesh.tris.push_back(t);
      const size_t face = i / 3;
      int mat = face < shape.mesh.material_ids.size() ? shape.mesh.material_ids[face] : -1;
      if (mat >= int(mesh.materials.size())) mat = -1;
      any_material = any_material || mat >= 0;
      mesh.material_ids.push_back(mat);
      // vn and vt, when every corner has them; OBJ's v points up the image, ours down.
      TriangleAttributes a;
      a.has_normals = a.has_uvs = true;
      for (int k = 0; k < 3; ++k) {
        const auto& c = idx[i + size_t(k)];
        check_attribute_index(c.normal_index, n_normals, "normal (vn)", file, face, shape.name);
        check_attribute_index(c.texcoord_index, n_uvs, "texture coordinate (vt)", file, face, shape.name);
        if (c.normal_index >= 0 && size_t(c.normal_index) < n_normals) {
          const float* n = &attrib.normals[3 * size_t(c.normal_index)];
          a.n[k] = Vec3(n[0], n[1], n[2]);
        } else {
          a.has_normals = false;
        }
        if (c.texcoord_index >= 0 && size_t(c.texcoord_index) < n_uvs) {
          const float* uv = &attrib.texcoords[2 * size_t(c.texcoord_index)];
          a.uv[k] = Vec2(uv[0], 1.0f - uv[1]);
        } else {
          a.has_uvs = false;
        }
      }
      any_attributes = any_attributes || a.has_normals || a.has_uvs;
      mesh.attributes.push_back(a);
    }
  }
  if (!any_attributes) mesh.attributes.clear();
  if (!any_material) mesh.material_ids.clear();
  if (mesh.tris.empty()) throw InputError("OBJ file " + file + " has no faces");
  return mesh;
}

}  // namespace caustica
