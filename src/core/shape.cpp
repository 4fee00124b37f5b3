// Triangle, sphere and SDF voxel geometry and intersection.
#include "core/shape.h"
#include <algorithm>
#include <cmath>
#include "core/sampling.h"

namespace caustica {

Primitive Primitive::triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  Primitive p;
  p.kind = ShapeKind::Triangle;
  p.p0 = a;
  p.p1 = b;
  p.p2 = c;
  p.ng = glm::normalize(glm::cross(b - a, c - a));
  return p;
}

Primitive Primitive::sphere(const Vec3& centre, float radius) {
  Primitive p;
  p.kind = ShapeKind::Sphere;
  p.p0 = centre;
  p.p1 = Vec3(radius, 0, 0);
  p.p2 = Vec3(0);
  return p;
}

Primitive Primitive::sdf_voxel(const SdfGrid* grid, uint32_t voxel) {
  Primitive p;
  p.kind = ShapeKind::SdfVoxel;
  const Bounds b = grid->voxel_bounds(voxel);
  p.p0 = b.lo;
  p.p1 = b.hi;
  p.set_p2(grid, voxel);
  return p;
}

Primitive Primitive::bspline_curve(const glm::vec4* cp, uint32_t segment, uint32_t segments) {
  Primitive p;
  p.kind = ShapeKind::BsplineCurve;
  // The spline lies in its control points' hull and its radius below their largest.
  Bounds b;
  float r = 0.0f;
  for (int i = 0; i < 4; ++i) {
    b.extend(Vec3(cp[i]));
    r = std::max(r, cp[i].w);
  }
  const Vec3 pad = Vec3(r) + 1e-6f * (glm::max(glm::abs(b.lo), glm::abs(b.hi)) + Vec3(r));
  p.p0 = b.lo - pad;
  p.p1 = b.hi + pad;
  p.set_p2(cp, segment);
  p.ng = Vec3(float(segments), 0.0f, 0.0f);
  return p;
}

Primitive Primitive::linear_curve(const Vec3& a, float ra, const Vec3& b, float rb, uint32_t segment, uint32_t segments) {
  Primitive p;
  p.kind = ShapeKind::LinearCurve;
  p.p0 = a;
  p.p1 = b;
  p.p2 = Vec3(ra, rb, float(segment));
  p.ng = Vec3(float(segments), 0.0f, 0.0f);
  return p;
}

Bounds Primitive::bounds() const {
  Bounds b;
  if (kind == ShapeKind::SdfVoxel || kind == ShapeKind::BsplineCurve) {
    b.extend(p0);
    b.extend(p1);
  } else if (kind == ShapeKind::LinearCurve) {
    // Both end spheres, a few ulps wider (the float box around a double-precision test).
    const Vec3 pad0 = Vec3(p2.x) + 1e-6f * (glm::abs(p0) + Vec3(p2.x)), pad1 = Vec3(p2.y) + 1e-6f * (glm::abs(p1) + Vec3(p2.y));
    b.extend(p0 - pad0);
    b.extend(p0 + pad0);
    b.extend(p1 - pad1);
    b.extend(p1 + pad1);
  } else if (kind == ShapeKind::Triangle) {
    b.extend(p0);
    b.extend(p1);
    b.extend(p2);
  } else {
    b.extend(p0 - Vec3(radius()));
    b.extend(p0 + Vec3(radius()));
  }
  return b;
}

Vec3 Primitive::centroid() const {
  if (kind != ShapeKind::Triangle && kind != ShapeKind::Sphere) return 0.5f * (p0 + p1);
  return kind == ShapeKind::Triangle ? (p0 + p1 + p2) / 3.0f : p0;
}

float Primitive::area() const {
  if (kind == ShapeKind::SdfVoxel) return 0.0f;  // not known in closed form; SDF grids do not emit (as in Mitsuba)
  if (kind == ShapeKind::BsplineCurve) {
    // Approximately: the mean radius over the control polygon's length (for statistics only).
    const glm::vec4* cp = bspline_points();
    float len = 0.0f;
    for (int i = 0; i < 3; ++i) len += glm::length(Vec3(cp[i + 1]) - Vec3(cp[i]));
    return kPi * (cp[1].w + cp[2].w) * len / 3.0f;
  }
  if (kind == ShapeKind::LinearCurve) {
    // The cone's side between its touching circles (the joints' spheres are shared with the
    // neighbours; curves do not emit here, and the figure serves the object's statistics).
    const float len = glm::length(p1 - p0);
    return kPi * (p2.x + p2.y) * len;
  }
  if (kind == ShapeKind::Triangle) return 0.5f * glm::length(glm::cross(p1 - p0, p2 - p0));
  return 4.0f * kPi * radius() * radius();
}

Primitive::AxisPoint Primitive::curve_axis_point(const Vec3& p) const {
  if (kind == ShapeKind::LinearCurve) {
    const float s = round_cone_parameter(p, p0, p2.x, p1, p2.y);
    return {s, p0 + s * (p1 - p0), p1 - p0};
  }
  const glm::vec4* cp = bspline_points();
  const float s = bspline_parameter(p, cp);
  return {s, Vec3(bspline_point(cp, s)), Vec3(bspline_tangent(cp, s))};
}

Vec3 Primitive::normal_at(const Vec3& p) const {
  Vec3 n;
  switch (kind) {
    case ShapeKind::Triangle: n = ng; break;
    case ShapeKind::Sphere: n = glm::normalize(p - p0); break;
    case ShapeKind::SdfVoxel: n = sdf_grid()->normal(p, sdf_voxel()); break;
    case ShapeKind::LinearCurve:
    case ShapeKind::BsplineCurve: return curve_normal(p, curve_axis_point(p));
  }
  return flip ? -n : n;
}

Vec3 Primitive::sample_point(const Vec2& u, Vec3* normal) const {
  Vec3 p;
  if (kind == ShapeKind::Triangle) {
    const Vec2 b = sample_uniform_triangle(u);
    p = b.x * p0 + b.y * p1 + (1.0f - b.x - b.y) * p2;
  } else {
    p = p0 + radius() * sample_uniform_sphere(u);
  }
  if (normal) *normal = normal_at(p);
  return p;
}

Vec3 barycentrics(const Primitive& t, const Vec3& p) {
  const Vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0, d = p - t.p0;
  const float d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const float d1 = glm::dot(d, e1), d2 = glm::dot(d, e2);
  const float denom = d11 * d22 - d12 * d12;
  if (!(denom > 0.0f)) return Vec3(1.0f, 0.0f, 0.0f);
  const float b1 = (d22 * d1 - d12 * d2) / denom, b2 = (d11 * d2 - d12 * d1) / denom;
  return Vec3(1.0f - b1 - b2, b1, b2);
}

Vec2 sphere_uv(const Vec3& d) {
  float u = std::atan2(d.y, d.x) * (0.5f * kInvPi);
  if (u < 0.0f) u += 1.0f;
  return Vec2(u, std::acos(std::clamp(d.z, -1.0f, 1.0f)) * kInvPi);
}

TexturePoint surface_point(const Primitive& prim, const TriangleAttributes* a, const Vec3& p) {
  if (prim.kind == ShapeKind::Sphere) return sphere_uv(glm::normalize(p - prim.p0));
  TexturePoint tp;
  if (!a || (!a->has_uvs && !a->mesh)) return tp;
  const Vec3 b = barycentrics(prim, p);
  if (a->has_uvs) tp.uv = b.x * a->uv[0] + b.y * a->uv[1] + b.z * a->uv[2];
  tp.mesh = a->mesh;
  tp.triangle = a->triangle;
  tp.bary = b;
  return tp;
}

bool intersect_triangle(const Ray& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                        float tmax, float& t, float& u, float& v) {
  return intersect_triangle_edges(ray, p0, p1 - p0, p2 - p0, tmax, t, u, v);
}

bool intersect_sphere(const Ray& ray, const Vec3& centre, float radius, float tmax, float& t) {
  const glm::dvec3 d(ray.dir);
  const glm::dvec3 f = glm::dvec3(ray.origin) - glm::dvec3(centre);
  const double r = radius;
  const double b = -glm::dot(f, d);  // ray.dir is unit length, so a = 1
  const glm::dvec3 l = f + b * d;    // closest approach, computed without cancellation
  const double disc = r * r - glm::dot(l, l);
  if (disc < 0.0) return false;
  const double c = glm::dot(f, f) - r * r;
  const double q = b + std::copysign(std::sqrt(disc), b);
  double t0 = c / q, t1 = q;
  if (q == 0.0) t0 = t1 = 0.0;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > 0.0 && t0 < tmax) {
    t = static_cast<float>(t0);
    return t > 0.0f;
  }
  if (t1 > 0.0 && t1 < tmax) {
    t = static_cast<float>(t1);
    return t > 0.0f;
  }
  return false;
}

}  // namespace caustica
