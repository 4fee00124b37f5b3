// Vectors, colours, rays and orthonormal frames on GLM (single precision).
#pragma once
#include <glm/glm.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

namespace caustica {

using Vec3 = glm::vec3;
using Vec2 = glm::vec2;
using Color = glm::vec3;

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 1.0f / kPi;
constexpr float kInfinity = std::numeric_limits<float>::infinity();
// How far from the origin a scene may reach. Past about 1.84e18 Embree refuses (and asserts on)
// a ray's origin, and well before that single-precision geometry overflows: a triangle's normal
// is the length of a cross product, a fourth power of the coordinates (finite up to about 2e9),
// and an area light's power its area times its radiance. Scene readers refuse positions, radii
// and apertures beyond this bound.
constexpr float kMaxCoordinate = 1e9f;
// The largest colour a scene may give (a radiance, an intensity, an irradiance, a texel of an
// environment map times its scale). The film sums samples exactly up to 1e12 each
// (core/fixed_sum.h), so what a light emits, times a path's throughput, stays well inside.
constexpr float kMaxColor = 1e9f;

inline float max_component(const Vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }
inline float luminance(const Color& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
inline float average(const Color& c) { return (c.r + c.g + c.b) / 3.0f; }
inline bool is_black(const Color& c) { return c.r == 0.0f && c.g == 0.0f && c.b == 0.0f; }
// v divided by its largest |component| (v itself when zero), so that its length can be taken:
// a float's overflows for vectors longer than about 1.8e19.
inline Vec3 scaled_to_unit_max(const Vec3& v) {
  const float m = max_component(glm::abs(v));
  return m > 0.0f ? v / m : v;
}
inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

struct Ray {
  Vec3 origin;
  Vec3 dir;  // unit length
  float tmax = kInfinity;
  Vec3 at(float t) const { return origin + t * dir; }
};

// Offsets a point leaving a surface so that the new ray does not hit the surface again.
// The offset grows with the coordinates' magnitude, where float rounding grows too.
inline Vec3 offset_origin(const Vec3& p, const Vec3& n, const Vec3& dir) {
  const float scale = 1.0f + std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
  const float eps = 2e-5f * scale;
  return glm::dot(dir, n) >= 0.0f ? p + eps * n : p - eps * n;
}

inline Ray spawn_ray(const Vec3& p, const Vec3& n, const Vec3& dir) {
  return Ray{offset_origin(p, n, dir), dir, kInfinity};
}

// Shadow ray from a surface point p (normal n) to a target point q (normal nq, or zero).
inline Ray spawn_ray_to(const Vec3& p, const Vec3& n, const Vec3& q, const Vec3& nq) {
  Vec3 d = q - p;
  const Vec3 o = offset_origin(p, n, d);
  const Vec3 target = glm::dot(nq, nq) > 0.0f ? offset_origin(q, nq, o - q) : q;
  d = target - o;
  const float len = glm::length(d);
  return Ray{o, d / len, len};
}

// Orthonormal frame around a unit normal (Duff et al. 2017, "Building an orthonormal basis, revisited").
struct Frame {
  Vec3 s, t, n;
  Frame() : s(1, 0, 0), t(0, 1, 0), n(0, 0, 1) {}
  explicit Frame(const Vec3& normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    s = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    t = Vec3(b, sign + n.y * n.y * a, -n.y);
  }
  // A frame whose s axis follows `tangent` (projected onto the plane of n), for anisotropic
  // BSDFs oriented by the surface's dp/du as in Mitsuba; falls back to Frame(n).
  Frame(const Vec3& normal, const Vec3& tangent) : Frame(normal) {
    const Vec3 ts = tangent - normal * glm::dot(normal, tangent);
    const float len = glm::length(ts);
    if (!(len > 1e-6f) || !std::isfinite(len)) return;
    s = ts / len;
    t = glm::cross(n, s);
  }
  Vec3 to_local(const Vec3& v) const { return Vec3(glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)); }
  Vec3 to_world(const Vec3& v) const { return v.x * s + v.y * t + v.z * n; }
};

}  // namespace caustica
