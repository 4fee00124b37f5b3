// The scene loader's state and steps, shared by its files: scene_loader.cpp (the document,
// integrator block, materials and lights), camera_reader.cpp (render block, filter, camera),
// shape_reader.cpp (the shape table, objects, spheres, triangles, quads) and mesh_reader.cpp
// (meshes inline and from files). Internal to src/io.
#pragma once
#include <map>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>
#include "io/json_reader.h"
#include "io/meshes/mesh_file.h"
#include "io/scene_loader.h"

namespace caustica::scene_loading {
using nlohmann::json;

struct Loader;

// The shape family's table: an object block's "type", the keys it may hold besides "type",
// "name", "material" and "flip_normal", and its reader. Mitsuba's shapes are translated into
// these (io/mitsuba/translate_shape.cpp).
struct ShapePlugin {
  const char* name;
  std::vector<const char*> keys;
  bool (Loader::*read)(const json& j, const std::string& p, std::vector<Primitive>& shapes);
};
const std::vector<ShapePlugin>& shape_plugins();

struct Loader {
  JsonReader r;
  std::string base_dir;
  RenderOverrides overrides;
  LoadedScene out;
  std::map<std::string, uint32_t> material_ids;
  std::vector<Primitive> prims;

  Scene& scene() { return *out.scene; }

  void load(const json& doc);

  void read_render(const json& j, const std::string& p);

  // The command line's values over the render block's, before the camera and the accelerator
  // are made.
  void apply_overrides();

  // "box", or {"type": "gaussian", "stddev": 0.5} or {"type": "tent", "radius": 1}.
  void read_filter(const json& j, const std::string& p);

  void read_camera(const json& j, const std::string& p);

  int crop_[4] = {0, 0, 0, 0};

  void read_integrator(const json& j, const std::string& p);

  void read_materials(const json& j, const std::string& p);

  // Reads a material block and adds it (and the materials nested in it) under `name`.
  uint32_t add_material(const std::string& name, const json& m, const std::string& p);

  uint32_t material_ref(const json& obj, const std::string& p, const char* key = "material");
  // For shapes that cannot be area lights: fails at p/material when its material emits.
  void refuse_emission(const json& obj, const std::string& p, const std::string& shape);

  // An object block through the shape table; each shape reader fills `shapes` with the object's
  // primitives, or adds its objects itself and returns true (a mesh file with its materials).
  void read_object(const json& j, const std::string& p);
  bool read_sphere(const json& j, const std::string& p, std::vector<Primitive>& shapes);
  bool read_triangle(const json& j, const std::string& p, std::vector<Primitive>& shapes);
  bool read_quad(const json& j, const std::string& p, std::vector<Primitive>& shapes);
  bool read_mesh_object(const json& j, const std::string& p, std::vector<Primitive>& shapes);
  bool read_sdfgrid(const json& j, const std::string& p, std::vector<Primitive>& shapes);
  bool read_linearcurve(const json& j, const std::string& p, std::vector<Primitive>& shapes);
  bool read_bsplinecurve(const json& j, const std::string& p, std::vector<Primitive>& shapes);
  void read_curves(const json& j, const std::string& p, std::vector<Primitive>& shapes, bool bspline);

  // Shapes of one material become one object (and one area light when the material emits).
  void add_object(std::vector<Primitive> shapes, uint32_t mat, const json& j, const std::string& p);

  // An OBJ whose .mtl names materials, in a scene that gives the object none: one object per
  // material, the materials translated (docs/scene-format.md, "Materials of mesh files").
  void add_mesh_with_its_materials(const json& j, const std::string& p, const MeshData& mesh);

  // OBJ/MTL terms in ours: Ke emits; illum 4, 6, 7 or d < 1 is glass of index Ni; a Ks with an
  // Ns is Phong (scaled so that Kd + Ks stays at most 1); else Lambertian Kd (or map_Kd).
  json mesh_material_json(const MeshMaterial& mm, const std::string& dir, const std::string& p);

  void add_triangle(std::vector<Primitive>& shapes, const Vec3& a, const Vec3& b, const Vec3& c, const std::string& p, const TriangleAttributes* attributes = nullptr);
  // An error at `p` when a point of an object lies past kMaxCoordinate (or is NaN).
  void check_reach(const Vec3& x, const std::string& p) const;

  void add_mesh_triangle(const MeshData& mesh, size_t i, std::vector<Primitive>& shapes, const std::string& p);

  // Per-vertex normals or UVs of an inline mesh: an array as long as "vertices".
  template <class T, class Read>
  std::vector<T> per_vertex(const json& j, const std::string& p, const char* key, size_t n, Read read) {
    std::vector<T> out;
    if (!j.contains(key)) return out;
    const json& a = j[key];
    if (!a.is_array() || a.size() != n) r.fail(child(p, key), "expected one entry per vertex (" + std::to_string(n) + ")");
    for (size_t i = 0; i < n; ++i) out.push_back(read(a[i], child(child(p, key), i)));
    return out;
  }

  MeshData read_mesh(const json& j, const std::string& p);
  // A mesh_attribute texture naming an attribute no mesh carries is an error at its place.
  void check_mesh_attribute_textures();
  std::map<const Texture*, std::string> texture_places_{};

  void read_light(const json& j, const std::string& p);
  // Participating media (the "media" block, by name), and the references to them: an object's
  // "interior" and "exterior", the camera's "medium" (medium_reader.cpp).
  void read_media(const json& j, const std::string& p);
  int32_t medium_ref(const json& obj, const std::string& p, const char* key);
  // The object's media interface (Primitive::media), 0 where it names none.
  uint16_t media_interface(const json& obj, const std::string& p);
  std::map<std::string, int32_t> medium_ids_{};
  std::map<std::pair<int32_t, int32_t>, uint16_t> interface_ids_{};
  // A light's or an emissive object's "sampling_weight" (positive).
  float sampling_weight(const json& j, const std::string& p) const;

  size_t degenerate_ = 0;
  std::vector<ColorParam> emission_{};  // by material id: the radiance of the area lights it makes
};

}  // namespace caustica::scene_loading
