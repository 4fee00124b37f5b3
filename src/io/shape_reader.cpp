// Objects: the shape family's table, and the sphere, triangle and quad readers; every object
// of an emitting material becomes an area light.
#include "io/loader.h"
#include "core/lights/area.h"
#include "io/json_params.h"

namespace caustica::scene_loading {

const std::vector<ShapePlugin>& shape_plugins() {
  static const std::vector<ShapePlugin> table = {
      {"sphere", {"center", "radius"}, &Loader::read_sphere},
      {"triangle", {"vertices"}, &Loader::read_triangle},
      {"quad", {"origin", "edge1", "edge2"}, &Loader::read_quad},
      {"mesh",
       {"vertices", "indices", "normals", "uvs", "file", "shape_index", "scale", "translate", "to_world", "face_normals",
        "default_material", "smooth_normals", "max_smooth_angle"},
       &Loader::read_mesh_object},
      {"sdfgrid", {"file", "to_world", "normals"}, &Loader::read_sdfgrid},
      {"linearcurve", {"file", "to_world"}, &Loader::read_linearcurve},
      {"bsplinecurve", {"file", "to_world"}, &Loader::read_bsplinecurve},
  };
  return table;
}

void Loader::read_object(const json& j, const std::string& p) {
  const ShapePlugin& row = plugin_row(r, j, p, shape_plugins(), "object",
                                      {"name", "material", "flip_normal", "sampling_weight", "interior", "exterior"});
  std::vector<Primitive> shapes;
  if ((this->*row.read)(j, p, shapes)) return;
  if (j.contains("name")) r.string(j["name"], child(p, "name"));
  add_object(std::move(shapes), material_ref(j, p), j, p);
}

bool Loader::read_sphere(const json& j, const std::string& p, std::vector<Primitive>& shapes) {
  const Vec3 c = r.vec3(r.require(j, p, "center"), child(p, "center"));
  const double radius = r.number(r.require(j, p, "radius"), child(p, "radius"));
  if (!(radius > 0.0)) r.fail(child(p, "radius"), "radius must be positive");
  shapes.push_back(Primitive::sphere(c, float(radius)));
  ++out.sphere_count;
  return false;
}

bool Loader::read_triangle(const json& j, const std::string& p, std::vector<Primitive>& shapes) {
  const json& v = r.require(j, p, "vertices");
  if (!v.is_array() || v.size() != 3) r.fail(child(p, "vertices"), "expected 3 vertices");
  add_triangle(shapes, r.vec3(v[0], child(p, "vertices/0")), r.vec3(v[1], child(p, "vertices/1")),
               r.vec3(v[2], child(p, "vertices/2")), p);
  return false;
}

bool Loader::read_quad(const json& j, const std::string& p, std::vector<Primitive>& shapes) {
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
  return false;
}

void Loader::add_object(std::vector<Primitive> shapes, uint32_t mat, const json& j, const std::string& p) {
  const bool flip = j.contains("flip_normal") && r.boolean(j["flip_normal"], child(p, "flip_normal"));
  if (j.contains("sampling_weight") && emission_[mat].is_black()) {
    r.fail(child(p, "sampling_weight"), "sampling_weight belongs to an object whose material emits");
  }
  if (shapes.empty()) {
    if (!emission_[mat].is_black()) r.fail(p, "emissive object has zero area (all its triangles are degenerate)");
    r.warn(p, "object has no usable triangles and is left out", out.warnings);
    return;
  }
  Bounds b;
  for (const Primitive& s : shapes) b.extend(s.bounds());
  check_reach(b.hi, p);
  check_reach(b.lo, p);
  int32_t light = -1;
  const uint16_t media = media_interface(j, p);
  for (Primitive& s : shapes) {
    s.material = mat;
    s.flip = flip;
    s.media = media;
  }
  if (!emission_[mat].is_black()) {
    light = static_cast<int32_t>(scene().lights.size());
    auto area_light = std::make_unique<AreaLight>(shapes, emission_[mat], scene().attributes);
    if (!(area_light->area() > 0.0f)) r.fail(p, "emissive object has zero area");
    if (j.contains("sampling_weight")) area_light->set_sampling_weight(sampling_weight(j, p));
    scene().lights.push_back(std::move(area_light));
  }
  ObjectInfo info;
  info.material = mat;
  if (shapes.size() == 1 && shapes[0].kind == ShapeKind::Sphere) {
    info.centre = shapes[0].p0;
    info.radius = shapes[0].radius();
  } else {
    info.centre = b.centre();
    for (const Primitive& s : shapes) {
      const Bounds sb = s.bounds();  // an SDF voxel's box (its p2 is not a point)
      const Vec3 corners[3] = {s.kind == ShapeKind::SdfVoxel ? sb.lo : s.p0, s.kind == ShapeKind::SdfVoxel ? sb.hi : s.p1,
                               s.kind == ShapeKind::SdfVoxel ? sb.hi : s.p2};
      for (const Vec3& v : corners) info.radius = std::max(info.radius, glm::length(v - info.centre));
    }
  }
  for (Primitive& s : shapes) {
    s.light = light;
    info.area += s.area();
    prims.push_back(s);
  }
  scene().objects.push_back(info);
}

void Loader::check_reach(const Vec3& x, const std::string& p) const {
  // Coordinate by coordinate: a NaN (inf - inf from a transform) fails too.
  for (int i = 0; i < 3; ++i) {
    if (!(std::abs(x[i]) <= kMaxCoordinate)) r.fail(p, out_of_scene_range("the object reaches " + format_number(x[i]) + ", which"));
  }
}

void Loader::add_triangle(std::vector<Primitive>& shapes, const Vec3& a, const Vec3& b, const Vec3& c, const std::string& p, const TriangleAttributes* attributes) {
  // Before the area test: a triangle out of range is an error, not a degenerate one.
  for (const Vec3* v : {&a, &b, &c}) check_reach(*v, p);
  const float area2 = glm::length(glm::cross(b - a, c - a));
  if (!(area2 > 0.0f) || !std::isfinite(area2)) {
    ++degenerate_;
    if (degenerate_ <= 3) r.warn(p, "degenerate triangle (zero area) left out", out.warnings);
    return;
  }
  shapes.push_back(Primitive::triangle(a, b, c));
  if (attributes && (attributes->has_normals || attributes->has_uvs || attributes->mesh)) {
    shapes.back().attributes = static_cast<uint32_t>(scene().attributes.size());
    scene().attributes.push_back(*attributes);
  }
  ++out.triangle_count;
}

}  // namespace caustica::scene_loading
