// Geometric primitives (triangles, spheres, SDF grid voxels), their bounds and ray intersection.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>
#include "core/curve.h"
#include "core/math.h"
#include "core/sdf_grid.h"
#include "core/textures/texture.h"

namespace caustica {

struct Bounds {
  Vec3 lo{kInfinity}, hi{-kInfinity};
  void extend(const Vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  void extend(const Bounds& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
  Vec3 centre() const { return 0.5f * (lo + hi); }
  Vec3 extent() const { return hi - lo; }
  bool empty() const { return lo.x > hi.x; }
  float surface_area() const {
    if (empty()) return 0.0f;
    const Vec3 d = extent();
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
  }
};

enum class ShapeKind : uint8_t { Triangle, Sphere, SdfVoxel, LinearCurve, BsplineCurve };
constexpr uint32_t kNoAttributes = 0xffffffffu;

// Values a mesh file gives per vertex or per face besides positions, normals and UVs (PLY's
// colours and other properties, .serialized's vertex colours), named as Mitsuba names them
// ("vertex_color", "face_id"), for the mesh_attribute texture. Stored per triangle: a vertex
// attribute's three corners, a face attribute's one value (a polygon's fan triangles share it).
struct MeshAttribute {
  std::string name;
  int channels = 3;  // 1 (a grey value) or 3
  bool per_face = false;
  std::vector<Color> values;  // 3 per triangle (vertex_), or 1 (face_)
  // The value at barycentrics b on the mesh's triangle t.
  Color at(uint32_t t, const Vec3& b) const {
    if (per_face) return values[t];
    return b.x * values[3 * size_t(t)] + b.y * values[3 * size_t(t) + 1] + b.z * values[3 * size_t(t) + 2];
  }
};
struct MeshAttributes {
  std::vector<MeshAttribute> list;
  const MeshAttribute* find(const std::string& name) const {
    for (const MeshAttribute& a : list) {
      if (a.name == name) return &a;
    }
    return nullptr;
  }
};

// Per-corner shading data of a triangle: interpolated vertex normals (smooth shading) and
// texture coordinates (Mitsuba's convention, (0, 0) at the image's top-left); the attributes of
// the mesh it belongs to (owned by the scene) and its index there.
struct TriangleAttributes {
  Vec3 n[3]{Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)};
  Vec2 uv[3]{Vec2(0.0f), Vec2(0.0f), Vec2(0.0f)};
  bool has_normals = false, has_uvs = false;
  const MeshAttributes* mesh = nullptr;
  uint32_t triangle = 0;
};

// A triangle (p0, p1, p2), a sphere (centre p0, radius p1.x), or a voxel of an SDF grid (its
// world box p0 to p1; p2 holds the grid, owned by the scene, and the voxel's index), or a round
// linear curve segment (from p0 to p1, radii p2.x and p2.y; p2.z its index in the curve file
// and ng.x the file's segment count, for its v coordinate), or a round B-spline curve segment
// (its box p0 to p1; p2 holds its four control points, owned by the scene, and its index in the
// file; ng.x the file's segment count). `flip` reverses the normal.
// One cache line each (the hit's surface data reads it right after the ray cast).
struct alignas(64) Primitive {
  Vec3 p0, p1, p2;
  Vec3 ng{0.0f};  // a triangle's unit winding normal, before `flip` (set by triangle())
  uint32_t material = 0;
  int32_t light = -1;  // index of the area light this primitive belongs to, or -1
  uint32_t attributes = kNoAttributes;  // index of the triangle's vertex normals and UVs in the scene
  ShapeKind kind = ShapeKind::Triangle;
  bool flip = false;
  uint16_t media = 0;  // 1 + its index in Scene::interfaces (the media on its two sides), or 0

  static Primitive triangle(const Vec3& a, const Vec3& b, const Vec3& c);
  static Primitive sphere(const Vec3& centre, float radius);
  static Primitive sdf_voxel(const SdfGrid* grid, uint32_t voxel);
  static Primitive linear_curve(const Vec3& a, float ra, const Vec3& b, float rb, uint32_t segment, uint32_t segments);
  static Primitive bspline_curve(const glm::vec4* control_points, uint32_t segment, uint32_t segments);
  float radius() const { return p1.x; }
  const SdfGrid* sdf_grid() const { return static_cast<const SdfGrid*>(p2_pointer()); }
  uint32_t sdf_voxel() const { return p2_index(); }
  const glm::vec4* bspline_points() const { return static_cast<const glm::vec4*>(p2_pointer()); }
  uint32_t curve_segment() const { return kind == ShapeKind::LinearCurve ? uint32_t(p2.z) : p2_index(); }
  uint32_t curve_segments() const { return std::max(uint32_t(ng.x), 1u); }
  // What p2 holds for an SDF voxel and a B-spline segment: a pointer and an index.
  void set_p2(const void* pointer, uint32_t index) {
    static_assert(sizeof(const void*) + sizeof(uint32_t) <= sizeof(Vec3), "p2 holds a pointer and an index");
    std::memcpy(&p2, &pointer, sizeof(pointer));
    std::memcpy(reinterpret_cast<char*>(&p2) + sizeof(pointer), &index, sizeof(index));
  }
  const void* p2_pointer() const {
    const void* p;
    std::memcpy(&p, &p2, sizeof(p));
    return p;
  }
  uint32_t p2_index() const {
    uint32_t v;
    std::memcpy(&v, reinterpret_cast<const char*>(&p2) + sizeof(const void*), sizeof(v));
    return v;
  }
  Bounds bounds() const;
  Vec3 centroid() const;
  float area() const;
  // Outward (or winding) normal at a point on the surface, after `flip`.
  Vec3 normal_at(const Vec3& p) const;
  // The nearest point of a curve segment's axis to a point p on its surface: the segment's
  // parameter s in [0, 1], the axis point there and the axis's (unnormalised) tangent.
  struct AxisPoint {
    float s;
    Vec3 centre, axis;
  };
  AxisPoint curve_axis_point(const Vec3& p) const;
  // The normal of a curve at p from its axis point, after `flip`.
  Vec3 curve_normal(const Vec3& p, const AxisPoint& a) const {
    const Vec3 n = glm::normalize(p - a.centre);
    return flip ? -n : n;
  }
  // Point at sample u, uniformly by area, with its normal.
  Vec3 sample_point(const Vec2& u, Vec3* normal) const;
};
static_assert(sizeof(Primitive) == 64, "a primitive fills one cache line");

// Barycentric coordinates of a point on a triangle (b0 for p0, b1 for p1, b2 for p2).
Vec3 barycentrics(const Primitive& t, const Vec3& p);
// Mitsuba's sphere parameterisation at unit direction d from the centre: u = phi / 2 pi around
// z, v = theta / pi from +z.
Vec2 sphere_uv(const Vec3& d);
// Where textures are looked up at a point p on a primitive: a sphere's (u, v) from its
// direction, a triangle's interpolated from its corners' (zero without attributes or UVs), and
// a mesh triangle's attributes with p's barycentrics.
TexturePoint surface_point(const Primitive& prim, const TriangleAttributes* attributes, const Vec3& p);

// Moller-Trumbore (1997). Returns true and t, barycentrics (u, v) for a hit with 0 < t < tmax.
bool intersect_triangle(const Ray& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                        float tmax, float& t, float& u, float& v);

// The same test with the edges e1 = p1 - p0, e2 = p2 - p0 precomputed (the BVH's hot loop).
inline bool intersect_triangle_edges(const Ray& ray, const Vec3& p0, const Vec3& e1, const Vec3& e2, float tmax, float& t,
                              float& u, float& v) {
  const Vec3 pvec = glm::cross(ray.dir, e2);
  const float det = glm::dot(e1, pvec);
  if (det == 0.0f || !std::isfinite(det)) return false;
  const float inv_det = 1.0f / det;
  const Vec3 tvec = ray.origin - p0;
  // Barycentric tests widened by a few ulps: neighbouring triangles then overlap by a hair
  // instead of leaving cracks along shared edges that rounding would open (closed glass
  // meshes must not leak). A double hit on an edge is harmless for the closest hit.
  constexpr float kEdgeSlack = 1e-6f;
  u = glm::dot(tvec, pvec) * inv_det;
  if (u < -kEdgeSlack || u > 1.0f + kEdgeSlack) return false;
  const Vec3 qvec = glm::cross(tvec, e1);
  v = glm::dot(ray.dir, qvec) * inv_det;
  if (v < -kEdgeSlack || u + v > 1.0f + kEdgeSlack) return false;
  t = glm::dot(e2, qvec) * inv_det;
  return t > 0.0f && t < tmax;
}

// Analytic sphere in double precision with the numerically stable root (Haines et al.,
// Ray Tracing Gems ch. 7), so rays from the surface and huge radii behave.
bool intersect_sphere(const Ray& ray, const Vec3& centre, float radius, float tmax, float& t);

inline bool intersect_primitive(const Ray& ray, const Primitive& p, float tmax, float& t) {
  float u, v;
  switch (p.kind) {
    case ShapeKind::Triangle: return intersect_triangle(ray, p.p0, p.p1, p.p2, tmax, t, u, v);
    case ShapeKind::Sphere: return intersect_sphere(ray, p.p0, p.radius(), tmax, t);
    case ShapeKind::SdfVoxel: return p.sdf_grid()->intersect(ray, p.sdf_voxel(), tmax, t);
    case ShapeKind::LinearCurve: return intersect_round_cone(ray, p.p0, p.p2.x, p.p1, p.p2.y, tmax, t);
    case ShapeKind::BsplineCurve: return intersect_bspline(ray, p.bspline_points(), tmax, t);
  }
  return false;
}

}  // namespace caustica
