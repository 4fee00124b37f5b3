// Scene file loader: every key validated, every error located by file and JSON pointer.
#include "io/scene_loader.h"
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include "io/bsdf_reader.h"
#include "io/image_io.h"
#include "io/json_reader.h"
#include "core/lights/area.h"
#include "core/lights/registry.h"
#include "io/meshes/mesh_file.h"

namespace caustica {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Loader {
  JsonReader r;
  std::string base_dir;
  RenderOverrides overrides;
  LoadedScene out;
  std::map<std::string, uint32_t> material_ids;
  std::vector<Primitive> prims;

  Scene& scene() { return *out.scene; }

  void load(const json& doc) {
    r.check_object(doc, "", {"camera", "render", "integrator", "materials", "objects", "lights"});
    if (doc.contains("render")) read_render(doc["render"], "/render");
    apply_overrides();
    read_camera(r.require(doc, "", "camera"), "/camera");
    if (doc.contains("integrator")) read_integrator(doc["integrator"], "/integrator");
    read_materials(r.require(doc, "", "materials"), "/materials");
    const json& objects = r.require(doc, "", "objects");
    if (!objects.is_array()) r.fail("/objects", "expected an array of objects");
    for (size_t i = 0; i < objects.size(); ++i) read_object(objects[i], child("/objects", i));
    if (doc.contains("lights")) {
      const json& lights = doc["lights"];
      if (!lights.is_array()) r.fail("/lights", "expected an array of lights");
      for (size_t i = 0; i < lights.size(); ++i) read_light(lights[i], child("/lights", i));
    }
    if (prims.empty()) r.fail("/objects", "the scene has no geometry");
    if (scene().lights.empty()) {
      r.warn("", "the scene has no lights (no emissive material, no point light): the image will be black",
             out.warnings);
    }
    scene().build(std::move(prims));
  }

  void read_render(const json& j, const std::string& p) {
    r.check_object(j, p, {"width", "height", "spp", "seed", "max_depth", "crop", "accel", "filter"});
    RenderSettings& rs = scene().render;
    if (j.contains("width")) rs.width = int(r.integer(j["width"], child(p, "width"), 1, 16384));
    if (j.contains("height")) rs.height = int(r.integer(j["height"], child(p, "height"), 1, 16384));
    if (j.contains("spp")) rs.spp = int(r.integer(j["spp"], child(p, "spp"), 1, 1 << 24));
    if (j.contains("seed")) rs.seed = uint64_t(r.integer(j["seed"], child(p, "seed"), 0, INT64_MAX));
    if (j.contains("max_depth")) rs.max_depth = int(r.integer(j["max_depth"], child(p, "max_depth"), 1, 1024));
    if (j.contains("filter")) read_filter(j["filter"], child(p, "filter"));
    if (j.contains("accel")) {
      const std::string a = r.string(j["accel"], child(p, "accel"));
      AccelKind kind;
      if (!parse_accel(a, kind)) r.fail(child(p, "accel"), "unknown accel \"" + a + "\" (known: bvh, embree)");
      bool fell_back = false;
      rs.accel = choose_accel(kind, &fell_back);
      if (fell_back) r.warn(child(p, "accel"), "this build has no Embree: our BVH casts the rays", out.warnings);
    }
    if (j.contains("crop")) {
      const json& c = j["crop"];
      const std::string cp = child(p, "crop");
      if (!c.is_array() || c.size() != 4) r.fail(cp, "expected [x, y, width, height] in pixels of the film");
      for (size_t i = 0; i < 4; ++i) crop_[i] = int(r.integer(c[i], child(cp, i), i < 2 ? 0 : 1, 16384));
      if (crop_[0] + crop_[2] > rs.width || crop_[1] + crop_[3] > rs.height) {
        r.fail(cp, "the crop window reaches outside the " + std::to_string(rs.width) + "x" + std::to_string(rs.height) + " film");
      }
    }
  }

  // The command line's values over the render block's, before the camera and the accelerator
  // are made.
  void apply_overrides() {
    RenderSettings& rs = scene().render;
    if (overrides.width || overrides.height) {
      rs.width = overrides.width.value_or(rs.width);
      rs.height = overrides.height.value_or(rs.height);
      crop_[2] = crop_[3] = 0;
    }
    if (overrides.spp) rs.spp = *overrides.spp;
    if (overrides.seed) rs.seed = *overrides.seed;
    if (overrides.max_depth) rs.max_depth = *overrides.max_depth;
    if (overrides.accel) rs.accel = choose_accel(overrides.accel);
  }

  // "box", or {"type": "gaussian", "stddev": 0.5} or {"type": "tent", "radius": 1}.
  void read_filter(const json& j, const std::string& p) {
    PixelFilter& f = scene().render.filter;
    if (j.is_string()) {
      const std::string t = r.string(j, p);
      if (t == "box") f = PixelFilter::box();
      else if (t == "gaussian") f = PixelFilter::gaussian(0.5f);
      else if (t == "tent") f = PixelFilter::tent(1.0f);
      else r.fail(p, "unknown filter \"" + t + "\" (known: box, gaussian, tent)");
      return;
    }
    const std::string t = r.string(r.require(j, p, "type"), child(p, "type"));
    if (t == "box") {
      r.check_object(j, p, {"type"});
      f = PixelFilter::box();
    } else if (t == "gaussian") {
      r.check_object(j, p, {"type", "stddev"});
      f = PixelFilter::gaussian(j.contains("stddev") ? float(r.number_in(j["stddev"], child(p, "stddev"), 0.05, 16.0)) : 0.5f);
    } else if (t == "tent") {
      r.check_object(j, p, {"type", "radius"});
      f = PixelFilter::tent(j.contains("radius") ? float(r.number_in(j["radius"], child(p, "radius"), 0.05, 16.0)) : 1.0f);
    } else {
      r.fail(child(p, "type"), "unknown filter \"" + t + "\" (known: box, gaussian, tent)");
    }
  }

  void read_camera(const json& j, const std::string& p) {
    r.check_object(j, p, {"position", "look_at", "up", "fov", "fov_axis", "mirror", "aperture_radius", "focus_distance"});
    const Vec3 pos = r.vec3(r.require(j, p, "position"), child(p, "position"));
    const Vec3 at = r.vec3(r.require(j, p, "look_at"), child(p, "look_at"));
    const Vec3 up = j.contains("up") ? r.vec3(j["up"], child(p, "up")) : Vec3(0, 1, 0);
    const float fov = j.contains("fov") ? float(r.number_in(j["fov"], child(p, "fov"), 0.1, 179.0)) : 45.0f;
    if (glm::length(at - pos) <= 0.0f) r.fail(child(p, "look_at"), "look_at equals position");
    if (glm::length(glm::cross(glm::normalize(at - pos), up)) < 1e-6f) {
      r.fail(child(p, "up"), "up is parallel to the viewing direction (or zero)");
    }
    RenderSettings& rs = scene().render;
    Camera& camera = scene().camera;
    camera = Camera(pos, at, up, fov, rs.width, rs.height);
    if (j.contains("fov_axis")) {
      static const std::map<std::string, FovAxis> axes = {{"x", FovAxis::X}, {"y", FovAxis::Y}, {"smaller", FovAxis::Smaller},
                                                          {"larger", FovAxis::Larger}, {"diagonal", FovAxis::Diagonal}};
      const std::string a = r.string(j["fov_axis"], child(p, "fov_axis"));
      const auto it = axes.find(a);
      if (it == axes.end()) r.fail(child(p, "fov_axis"), "unknown fov_axis \"" + a + "\" (known: x, y, smaller, larger, diagonal)");
      camera.set_fov(fov, it->second);
    }
    if (j.contains("mirror")) camera.set_mirror(r.boolean(j["mirror"], child(p, "mirror")));
    if (j.contains("aperture_radius") || j.contains("focus_distance")) {
      const float radius = float(r.number_in(r.require(j, p, "aperture_radius"), child(p, "aperture_radius"), 0.0, 1e30));
      const double focus = r.number(r.require(j, p, "focus_distance"), child(p, "focus_distance"));
      if (!(float(focus) > 0.0f)) r.fail(child(p, "focus_distance"), "focus_distance must be positive");
      camera.set_lens(radius, float(focus));
    }
    if (crop_[2] > 0) {
      camera.set_crop(crop_[0], crop_[1], crop_[2], crop_[3]);
      rs.width = crop_[2];
      rs.height = crop_[3];
    }
  }

  int crop_[4] = {0, 0, 0, 0};

  void read_integrator(const json& j, const std::string& p) {
    if (!j.is_object()) r.fail(p, "expected an object");
    JsonSource& src = out.integrator_settings;
    src.file = r.file();
    src.pointer = p;
    src.sources = r.sources();
    src.value = json::object();
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (it.key() == "type") {
        out.integrator_type = r.string(it.value(), child(p, "type"));
      } else {
        src.value[it.key()] = it.value();
      }
    }
  }

  void read_materials(const json& j, const std::string& p) {
    if (!j.is_object()) r.fail(p, "expected an object mapping names to materials");
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string mp = child(p, it.key());
      const json& m = it.value();
      if (!m.is_object()) r.fail(mp, "expected an object");
      add_material(it.key(), m, mp);
    }
  }

  // Reads a material block and adds it (and the materials nested in it) under `name`.
  uint32_t add_material(const std::string& name, const json& m, const std::string& p) {
    std::vector<std::unique_ptr<Bsdf>> nested;
    const PluginContext ctx{r, base_dir, nested, scene().textures, out.warnings};
    std::unique_ptr<Bsdf> mat = read_bsdf(ctx, m, p);
    for (auto& n : nested) {
      scene().materials.push_back(std::move(n));
      scene().material_names.push_back(name + " (nested)");
      emission_.push_back(Color(0.0f));
    }
    const uint32_t id = static_cast<uint32_t>(scene().materials.size());
    material_ids[name] = id;
    scene().materials.push_back(std::move(mat));
    scene().material_names.push_back(name);
    emission_.push_back(m.contains("emission") ? r.color(m["emission"], child(p, "emission")) : Color(0.0f));
    return id;
  }

  uint32_t material_ref(const json& obj, const std::string& p, const char* key = "material") {
    const std::string name = r.string(r.require(obj, p, key), child(p, key));
    auto it = material_ids.find(name);
    if (it == material_ids.end()) {
      std::string known;
      for (const auto& kv : material_ids) known += (known.empty() ? "" : ", ") + kv.first;
      r.fail(child(p, key), "unknown material \"" + name + "\" (known: " + known + ")");
    }
    return it->second;
  }

  void read_object(const json& j, const std::string& p) {
    if (!j.is_object()) r.fail(p, "expected an object");
    const std::string type = r.string(r.require(j, p, "type"), child(p, "type"));
    std::vector<Primitive> shapes;
    if (type == "sphere") {
      r.check_object(j, p, {"type", "name", "material", "flip_normal", "center", "radius"});
      const Vec3 c = r.vec3(r.require(j, p, "center"), child(p, "center"));
      const double radius = r.number(r.require(j, p, "radius"), child(p, "radius"));
      if (!(radius > 0.0)) r.fail(child(p, "radius"), "radius must be positive");
      shapes.push_back(Primitive::sphere(c, float(radius)));
      ++out.sphere_count;
    } else if (type == "triangle") {
      r.check_object(j, p, {"type", "name", "material", "flip_normal", "vertices"});
      const json& v = r.require(j, p, "vertices");
      if (!v.is_array() || v.size() != 3) r.fail(child(p, "vertices"), "expected 3 vertices");
      add_triangle(shapes, r.vec3(v[0], child(p, "vertices/0")), r.vec3(v[1], child(p, "vertices/1")),
                   r.vec3(v[2], child(p, "vertices/2")), p);
    } else if (type == "quad") {
      r.check_object(j, p, {"type", "name", "material", "flip_normal", "origin", "edge1", "edge2"});
      const Vec3 o = r.vec3(r.require(j, p, "origin"), child(p, "origin"));
      const Vec3 e1 = r.vec3(r.require(j, p, "edge1"), child(p, "edge1"));
      const Vec3 e2 = r.vec3(r.require(j, p, "edge2"), child(p, "edge2"));
      if (!(glm::length(glm::cross(e1, e2)) > 0.0f)) r.fail(p, "quad has zero area (edges parallel or zero)");
      // UVs along the edges: (0, 0) at the origin, (1, 0) at origin + edge1, (0, 1) at origin + edge2.
      TriangleAttributes a;
      a.has_uvs = true;
      a.uv[0] = Vec2(0, 0), a.uv[1] = Vec2(1, 0), a.uv[2] = Vec2(1, 1);
      add_triangle(shapes, o, o + e1, o + e1 + e2, p, &a);
      a.uv[1] = Vec2(1, 1), a.uv[2] = Vec2(0, 1);
      add_triangle(shapes, o, o + e1 + e2, o + e2, p, &a);
    } else if (type == "mesh") {
      r.check_object(j, p, {"type", "name", "material", "flip_normal", "vertices", "indices", "normals", "uvs", "file",
                            "shape_index", "scale", "translate", "to_world", "face_normals", "default_material",
                            "smooth_normals"});
      if (j.contains("default_material") && j.contains("material")) {
        r.fail(child(p, "default_material"), "give material or default_material, not both");
      }
      MeshData mesh = read_mesh(j, p);
      if (!j.contains("material") && !mesh.material_ids.empty()) {
        add_mesh_with_its_materials(j, p, mesh);
        return;
      }
      for (size_t i = 0; i < mesh.tris.size(); ++i) add_mesh_triangle(mesh, i, shapes, p);
      if (j.contains("default_material")) {
        add_object(std::move(shapes), material_ref(j, p, "default_material"), j, p);
        return;
      }
    } else {
      r.fail(child(p, "type"), "unknown object type \"" + type + "\" (known: sphere, triangle, quad, mesh)");
    }
    if (j.contains("name")) r.string(j["name"], child(p, "name"));
    if (type == "mesh" && !j.contains("material") && j.contains("file")) {
      r.fail(p, "missing key \"material\" (the mesh file names no materials of its own)");
    }
    add_object(std::move(shapes), material_ref(j, p), j, p);
  }

  // Shapes of one material become one object (and one area light when the material emits).
  void add_object(std::vector<Primitive> shapes, uint32_t mat, const json& j, const std::string& p) {
    const bool flip = j.contains("flip_normal") && r.boolean(j["flip_normal"], child(p, "flip_normal"));
    if (shapes.empty()) {
      if (!is_black(emission_[mat])) r.fail(p, "emissive object has zero area (all its triangles are degenerate)");
      r.warn(p, "object has no usable triangles and is left out", out.warnings);
      return;
    }
    int32_t light = -1;
    for (Primitive& s : shapes) {
      s.material = mat;
      s.flip = flip;
    }
    if (!is_black(emission_[mat])) {
      light = static_cast<int32_t>(scene().lights.size());
      auto area_light = std::make_unique<AreaLight>(shapes, emission_[mat]);
      if (!(area_light->area() > 0.0f)) r.fail(p, "emissive object has zero area");
      scene().lights.push_back(std::move(area_light));
    }
    ObjectInfo info;
    info.material = mat;
    if (shapes.size() == 1 && shapes[0].kind == ShapeKind::Sphere) {
      info.centre = shapes[0].p0;
      info.radius = shapes[0].radius();
    } else {
      Bounds b;
      for (const Primitive& s : shapes) b.extend(s.bounds());
      info.centre = b.centre();
      for (const Primitive& s : shapes) {
        for (const Vec3& v : {s.p0, s.p1, s.p2}) info.radius = std::max(info.radius, glm::length(v - info.centre));
      }
    }
    for (Primitive& s : shapes) {
      s.light = light;
      info.area += s.area();
      prims.push_back(s);
    }
    scene().objects.push_back(info);
  }

  // An OBJ whose .mtl names materials, in a scene that gives the object none: one object per
  // material, the materials translated (docs/scene-format.md, "Materials of mesh files").
  void add_mesh_with_its_materials(const json& j, const std::string& p, const MeshData& mesh) {
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

  // OBJ/MTL terms in ours: Ke emits; illum 4, 6, 7 or d < 1 is glass of index Ni; a Ks with an
  // Ns is Phong (scaled so that Kd + Ks stays at most 1); else Lambertian Kd (or map_Kd).
  json mesh_material_json(const MeshMaterial& mm, const std::string& dir, const std::string& p) {
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

  void add_triangle(std::vector<Primitive>& shapes, const Vec3& a, const Vec3& b, const Vec3& c, const std::string& p,
                    const TriangleAttributes* attributes = nullptr) {
    const float area2 = glm::length(glm::cross(b - a, c - a));
    if (!(area2 > 0.0f) || !std::isfinite(area2)) {
      ++degenerate_;
      if (degenerate_ <= 3) r.warn(p, "degenerate triangle (zero area) left out", out.warnings);
      return;
    }
    shapes.push_back(Primitive::triangle(a, b, c));
    if (attributes && (attributes->has_normals || attributes->has_uvs)) {
      shapes.back().attributes = static_cast<uint32_t>(scene().attributes.size());
      scene().attributes.push_back(*attributes);
    }
    ++out.triangle_count;
  }

  void add_mesh_triangle(const MeshData& mesh, size_t i, std::vector<Primitive>& shapes, const std::string& p) {
    const glm::ivec3& t = mesh.tris[i];
    add_triangle(shapes, mesh.verts[size_t(t.x)], mesh.verts[size_t(t.y)], mesh.verts[size_t(t.z)], p,
                 mesh.attributes.empty() ? nullptr : &mesh.attributes[i]);
  }

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

  // An affine transform as 3 or 4 rows of 4 numbers (the last row, if given, must be 0 0 0 1).
  glm::mat4 read_affine(const json& m, const std::string& p) {
    if (!m.is_array() || (m.size() != 3 && m.size() != 4)) r.fail(p, "expected a 4x4 matrix (an array of 4 rows of 4 numbers)");
    glm::mat4 out(1.0f);
    for (size_t row = 0; row < m.size(); ++row) {
      const json& rw = m[row];
      if (!rw.is_array() || rw.size() != 4) r.fail(child(p, row), "expected a row of 4 numbers");
      for (size_t col = 0; col < 4; ++col) out[int(col)][int(row)] = float(r.number(rw[col], child(child(p, row), col)));
    }
    if (out[0][3] != 0.0f || out[1][3] != 0.0f || out[2][3] != 0.0f || out[3][3] != 1.0f) {
      r.fail(p, "the last row must be [0, 0, 0, 1] (projective transforms are not supported)");
    }
    // Singular relative to the columns' lengths, so that small (and large) scales are fine.
    const glm::mat3 l(out);
    const float scale = glm::length(l[0]) * glm::length(l[1]) * glm::length(l[2]);
    if (!(std::abs(glm::determinant(l)) > 1e-6f * scale)) r.fail(p, "the transform is singular (it flattens the shape)");
    return out;
  }

  MeshData read_mesh(const json& j, const std::string& p) {
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
      const std::string file = r.string(r.require(j, p, "file"), child(p, "file"));
      const int shape_index = j.contains("shape_index") ? int(r.integer(j["shape_index"], child(p, "shape_index"), 0, INT32_MAX)) : 0;
      const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : fs::path(base_dir) / file;
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
    const glm::mat4 to_world = has_matrix ? read_affine(j["to_world"], child(p, "to_world")) : glm::mat4(1.0f);
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(to_world)));
    const bool face_normals = j.contains("face_normals") && r.boolean(j["face_normals"], child(p, "face_normals"));
    if (j.contains("smooth_normals") && r.boolean(j["smooth_normals"], child(p, "smooth_normals"))) {
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
    return mesh;
  }

  void read_light(const json& j, const std::string& p) {
    const LightPlugin& row = plugin_row(r, j, p, light_plugins(), "light", {"name"},
                                        "; area lights are objects with an emissive material");
    if (j.contains("name")) r.string(j["name"], child(p, "name"));
    std::vector<std::unique_ptr<Bsdf>> nested;
    const PluginContext ctx{r, base_dir, nested, scene().textures, out.warnings};
    scene().lights.push_back(row.create(JsonParams(ctx, j, p)));
  }

  size_t degenerate_ = 0;
  std::vector<Color> emission_{};  // by material id: the radiance of the area lights it makes
};

}  // namespace

LoadedScene parse_scene(const std::string& text, const std::string& file, const std::string& base_dir,
                        const MitsubaOptions& mitsuba, const RenderOverrides& overrides) {
  json doc;
  std::shared_ptr<const SourceMap> sources;
  std::vector<std::string> warnings;
  if (looks_like_xml(text)) {
    TranslatedScene t = read_mitsuba(text, file, base_dir, mitsuba);
    doc = std::move(t.doc);
    sources = std::move(t.sources);
    warnings = std::move(t.warnings);
  } else {
    doc = parse_json_text(text, file);
  }
  Loader loader{JsonReader(file, sources), base_dir, overrides, {}, {}, {}};
  loader.out.scene = std::make_unique<Scene>();
  loader.out.scene->source_file = file;
  loader.out.warnings = std::move(warnings);
  loader.load(doc);
  if (loader.degenerate_ > 3) {
    loader.out.warnings.push_back(file + ": " + std::to_string(loader.degenerate_) +
                                  " degenerate triangles left out in all");
  }
  return std::move(loader.out);
}

LoadedScene load_scene(const std::string& path, const MitsubaOptions& mitsuba, const RenderOverrides& overrides) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path + ": scene file not found");
  if (fs::is_directory(path, ec)) throw InputError(path + ": is a directory, not a scene file");
  // A FIFO or device would block or never end: only regular files are read.
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open scene file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(path + ": error while reading the scene file");
  const std::string base = fs::path(path).parent_path().string();
  return parse_scene(ss.str(), path, base.empty() ? "." : base, mitsuba, overrides);
}

}  // namespace caustica
