// Light bounds: cone union and the importance at a point.
#include "core/light_bounds.h"
#include <algorithm>
#include <cmath>

namespace caustica {
namespace {
float safe_acos(float c) { return std::acos(std::clamp(c, -1.0f, 1.0f)); }
float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }

// v turned by angle about the unit axis k (Rodrigues).
Vec3 rotate(const Vec3& v, const Vec3& k, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (1.0f - c));
}
}  // namespace

DirectionCone DirectionCone::unite(const DirectionCone& a, const DirectionCone& b) {
  const float theta_a = safe_acos(a.cos_theta), theta_b = safe_acos(b.cos_theta);
  const float theta_d = safe_acos(glm::dot(a.axis, b.axis));
  if (std::min(theta_d + theta_b, kPi) <= theta_a) return a;
  if (std::min(theta_d + theta_a, kPi) <= theta_b) return b;
  // The cone whose edge touches both cones' far edges: half-angle (theta_a + theta_d +
  // theta_b) / 2, its axis turned from a's towards b's.
  const float theta_o = 0.5f * (theta_a + theta_d + theta_b);
  if (theta_o >= kPi) return everywhere();
  const Vec3 k = glm::cross(a.axis, b.axis);
  const float k_len = glm::length(k);
  if (!(k_len > 1e-7f)) return everywhere();
  const Vec3 axis = glm::normalize(rotate(a.axis, k / k_len, theta_o - theta_a));
  return {axis, std::cos(theta_o)};
}

LightBounds LightBounds::unite(const LightBounds& a, const LightBounds& b) {
  if (a.phi <= 0.0f) return b;
  if (b.phi <= 0.0f) return a;
  LightBounds u;
  u.bounds = a.bounds;
  u.bounds.extend(b.bounds);
  u.normals = DirectionCone::unite(a.normals, b.normals);
  u.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  u.phi = a.phi + b.phi;
  return u;
}

CompactLightBounds::CompactLightBounds(const LightBounds& b)
    : centre(b.bounds.centre()),
      r2(0.25f * glm::dot(b.bounds.extent(), b.bounds.extent())),
      r(std::sqrt(r2)),
      axis(b.normals.axis),
      cos_o(b.normals.cos_theta),
      sin_o(safe_sqrt(1.0f - b.normals.cos_theta * b.normals.cos_theta)),
      cos_e(b.cos_theta_e),
      phi(b.phi > 0.0f ? b.phi : 0.0f) {}

}  // namespace caustica
