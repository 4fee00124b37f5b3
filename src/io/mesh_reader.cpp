// The `mesh` shape: inline vertices and indices or a mesh file (OBJ, PLY, .serialized), with
// transforms, normals, UVs, and the materials an OBJ's .mtl names.
#include "io/loader.h"
#include <algorithm>
#include <filesystem>
#include "core/textures/mesh_attribute.h"
#include "io/json_params.h"

namespace caustica::scene_loading {

namespace fs = std::filesystem;

bool Loader::read_mesh_object(const json& j, const std::string& p, std::vector<Primitive>& shapes) {
  if (j.contains("default_material") && j.contains("material")) {
    r.fail(child(p, "default_material"), "give material or default_material, not both");
  }
  MeshData mesh = read_mesh(j, p);
  if (!j.contains("material") && !mesh.material_ids.empty()) {
    add_mesh_with_its_materials(j, p, mesh);
    return true;
  }
  for (size_t i = 0; i < mesh.tris.size(); ++i) add_mesh_triangle(mesh, i, shapes, p);
  if (j.contains("default_material")) {
    add_object(std::move(shapes), material_ref(j, p, "default_material"), j, p);
    return true;
  }
  if (j.contains("name")) r.string(j["name"], child(p, "name"));
  if (!j.contains("material") && j.contains("file")) {
    r.fail(p, "missing key \"material\" (the mesh file names no materials of its own)");
  }
  return false;
}

void Loader::add_mesh_with_its_materials(const json& j, const std::string& p, const MeshData& mesh) {
  const std::string file = r.string(j["file"], child(p, "file"));
  std::map<int, std::vector<Primitive>> groups;
  for (size_t i = 0; i < mesh.tris.size(); ++i) add_mesh_triangle(mesh, i, groups[mesh.material_ids[i]], p);
  for (auto& [id, shapes] : groups) {
    if (id < 0 && j.contains("default_material")) {
      add_object(std::move(shapes), material_ref(j, p, "default_material"), j, p);
      continue;
    }
    const std::string key = file + (id >= 0 ? "#" + mesh.materials[size_t(id)].name : "#(none)");
    auto it = material_ids.find(key);
    if (it == material_ids.end()) {
      json m = id >= 0 ? mesh_material_json(mesh.materials[size_t(id)], mesh.material_dir, p) : json{{"type", "diffuse"}, {"reflectance", 0.5}};
      if (id < 0) r.warn(p, "faces without a material in " + file + " get a grey diffuse one", out.warnings);
      add_material(key, m, p + " (material \"" + key + "\" of the mesh file)");
      it = material_ids.find(key);
    }
    add_object(std::move(shapes), it->second, j, p);
  }
}

json Loader::mesh_material_json(const MeshMaterial& mm, const std::string& dir, const std::string& p) {
  auto rgb = [](const Color& c) { return json::array({c.x, c.y, c.z}); };
  json m;
  if (mm.illum == 4 || mm.illum == 6 || mm.illum == 7 || mm.d < 1.0f) {
    m = {{"type", "dielectric"}, {"int_ior", mm.ni > 1.0f ? mm.ni : 1.5f}};
  } else {
    json kd = rgb(mm.kd);
    if (!mm.map_kd.empty()) {
      const fs::path tex = fs::path(mm.map_kd).is_absolute() ? fs::path(mm.map_kd) : fs::path(dir) / mm.map_kd;
      kd = {{"type", "bitmap"}, {"filename", fs::absolute(tex).string()}};
    }
    const float sum = max_component(mm.kd + mm.ks);
    if (!is_black(mm.ks) && mm.ns > 0.0f) {
      const float s = sum > 1.0f ? 1.0f / sum : 1.0f;
      if (sum > 1.0f) r.warn(p, "material \"" + mm.name + "\": Kd + Ks exceeds 1 and is scaled down", out.warnings);
      if (kd.is_array()) kd = rgb(mm.kd * s);
      m = {{"type", "phong"}, {"diffuse_reflectance", kd}, {"specular_reflectance", rgb(mm.ks * s)}, {"exponent", mm.ns}};
    } else {
      m = {{"type", "diffuse"}, {"reflectance", kd}};
    }
  }
  if (!is_black(mm.ke)) m["emission"] = rgb(mm.ke);
  return m;
}

void Loader::add_mesh_triangle(const MeshData& mesh, size_t i, std::vector<Primitive>& shapes, const std::string& p) {
  const glm::ivec3& t = mesh.tris[i];
  add_triangle(shapes, mesh.verts[size_t(t.x)], mesh.verts[size_t(t.y)], mesh.verts[size_t(t.z)], p,
               mesh.attributes.empty() ? nullptr : &mesh.attributes[i]);
}

MeshData Loader::read_mesh(const json& j, const std::string& p) {
  MeshData mesh;
  std::vector<Vec3>& verts = mesh.verts;
  const bool inline_mesh = j.contains("vertices") || j.contains("indices");
  if (inline_mesh && j.contains("file")) r.fail(p, "give either \"file\" or \"vertices\" and \"indices\", not both");
  if (inline_mesh) {
    if (j.contains("shape_index")) r.fail(child(p, "shape_index"), "shape_index applies to mesh files only");
    const json& v = r.require(j, p, "vertices");
    const json& ix = r.require(j, p, "indices");
    if (!v.is_array()) r.fail(child(p, "vertices"), "expected an array of [x, y, z]");
    if (!ix.is_array()) r.fail(child(p, "indices"), "expected an array of [i, j, k]");
    for (size_t i = 0; i < v.size(); ++i) verts.push_back(r.vec3(v[i], child(child(p, "vertices"), i)));
    for (size_t i = 0; i < ix.size(); ++i) {
      const std::string tp = child(child(p, "indices"), i);
      if (!ix[i].is_array() || ix[i].size() != 3) r.fail(tp, "expected 3 vertex indices");
      glm::ivec3 t;
      for (int k = 0; k < 3; ++k) t[k] = int(r.integer(ix[i][k], child(tp, size_t(k)), 0, int64_t(verts.size()) - 1));
      mesh.tris.push_back(t);
    }
    const auto normals = per_vertex<Vec3>(j, p, "normals", verts.size(),
                                          [&](const json& x, const std::string& xp) { return r.vec3(x, xp); });
    const auto uvs = per_vertex<Vec2>(j, p, "uvs", verts.size(),
                                      [&](const json& x, const std::string& xp) { return r.vec2(x, xp, "[u, v]"); });
    set_vertex_attributes(mesh, normals, uvs);
  } else {
    const fs::path path = r.input_file(r.require(j, p, "file"), child(p, "file"), base_dir, "mesh file");
    const int shape_index = j.contains("shape_index") ? int(r.integer(j["shape_index"], child(p, "shape_index"), 0, INT32_MAX)) : 0;
    try {
      mesh = read_mesh_file(path.string(), shape_index);
    } catch (const InputError& e) {
      r.fail(child(p, "file"), e.what());
    }
  }
  Vec3 scale(1.0f), translate(0.0f);
  if (j.contains("scale")) {
    scale = j["scale"].is_number() ? Vec3(float(r.number(j["scale"], child(p, "scale"))))
                                   : r.vec3(j["scale"], child(p, "scale"));
  }
  if (j.contains("translate")) translate = r.vec3(j["translate"], child(p, "translate"));
  const bool has_matrix = j.contains("to_world");
  const glm::mat4 to_world = has_matrix ? read_affine(r, j["to_world"], child(p, "to_world")) : glm::mat4(1.0f);
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(to_world)));
  const bool face_normals = j.contains("face_normals") && r.boolean(j["face_normals"], child(p, "face_normals"));
  if (j.contains("max_smooth_angle")) {
    const double degrees = r.number_in(j["max_smooth_angle"], child(p, "max_smooth_angle"), 0.0, 180.0);
    if (face_normals) r.fail(child(p, "max_smooth_angle"), "max_smooth_angle and face_normals exclude each other");
    rebuild_normals_with_creases(mesh, degrees);
  } else if (j.contains("smooth_normals") && r.boolean(j["smooth_normals"], child(p, "smooth_normals"))) {
    if (face_normals) r.fail(child(p, "smooth_normals"), "smooth_normals and face_normals exclude each other");
    add_smooth_normals(mesh);
  }
  for (Vec3& v : verts) {
    v = v * scale + translate;
    if (has_matrix) v = Vec3(to_world * glm::vec4(v, 1.0f));
  }
  for (TriangleAttributes& a : mesh.attributes) {
    if (face_normals) a.has_normals = false;
    // Normals transform by the inverse transpose.
    for (Vec3& n : a.n) {
      n = n / scale;
      if (has_matrix) n = normal_matrix * n;
    }
  }
  // The scene keeps the mesh's attributes, its triangles point at them, when a mesh_attribute
  // texture may read them (materials are read before objects); else they cost memory for nothing.
  const bool wanted = std::any_of(scene().textures.begin(), scene().textures.end(), [](const auto& t) {
    return dynamic_cast<const MeshAttributeTexture*>(t.get()) != nullptr;
  });
  if (!wanted) mesh.extra.list.clear();
  if (!mesh.extra.list.empty()) {
    scene().mesh_attributes.push_back(std::make_unique<MeshAttributes>(std::move(mesh.extra)));
    mesh.attributes.resize(mesh.tris.size());
    for (size_t i = 0; i < mesh.tris.size(); ++i) {
      mesh.attributes[i].mesh = scene().mesh_attributes.back().get();
      mesh.attributes[i].triangle = uint32_t(i);
    }
  }
  return mesh;
}

}  // namespace caustica::scene_loading
