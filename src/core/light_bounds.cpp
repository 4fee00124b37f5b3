// Light bounds: cone union and the importance at a point.
#include "core/light_bounds.h"
#include <algorithm>
#include <cmath>

namespace caustica {
namespace {
float safe_acos(float c) { return std::acos(std::clamp(c, -1.0f, 1.0f)); }
float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }

// cos(max(0, a - b)) and sin(max(0, a - b)) from the sines and cosines of angles a, b in [0, pi].
void subtract_clamped(float sin_a, float cos_a, float sin_b, float cos_b, float& sin_d, float& cos_d) {
  if (cos_a >= cos_b) {  // a <= b
    sin_d = 0.0f;
    cos_d = 1.0f;
    return;
  }
  cos_d = cos_a * cos_b + sin_a * sin_b;
  sin_d = sin_a * cos_b - cos_a * sin_b;
}

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

float LightBounds::importance(const Vec3& p, const Vec3& n) const {
  if (!(phi > 0.0f)) return 0.0f;
  const Vec3 centre = bounds.centre();
  const float r2 = 0.25f * glm::dot(bounds.extent(), bounds.extent());
  const float d2_centre = glm::dot(p - centre, p - centre);
  // Within the bounding sphere the bounds may lie in any direction (and the squared distance
  // is clamped to its radius's, else a point at the centre would have infinite importance).
  const float d2 = std::max({d2_centre, r2, 1e-12f});
  float sin_b = 0.0f, cos_b = -1.0f;
  if (d2_centre > r2) {
    const float sin2 = r2 / d2_centre;
    sin_b = std::sqrt(sin2);
    cos_b = safe_sqrt(1.0f - sin2);
  } else {
    sin_b = 0.0f;
  }
  const Vec3 wi = d2_centre > 0.0f ? (p - centre) / std::sqrt(d2_centre) : normals.axis;  // light to p
  // The angle between the cone and p's direction, less the cone's and the bounds' angles.
  const float cos_w = glm::dot(normals.axis, wi), sin_w = safe_sqrt(1.0f - cos_w * cos_w);
  const float cos_o = normals.cos_theta, sin_o = safe_sqrt(1.0f - cos_o * cos_o);
  float sin_x, cos_x, sin_p, cos_p;
  subtract_clamped(sin_w, cos_w, sin_o, cos_o, sin_x, cos_x);
  subtract_clamped(sin_x, cos_x, sin_b, cos_b, sin_p, cos_p);
  if (cos_p < cos_theta_e) return 0.0f;
  // A spot's cone (cos_theta_e 1) sends its intensity undiminished within it.
  float importance = phi * (cos_theta_e >= 1.0f ? 1.0f : std::max(cos_p, 0.0f)) / d2;
  if (n != Vec3(0.0f)) {
    // The least angle of incidence at p (either side: surfaces may transmit).
    const float cos_i = std::abs(glm::dot(wi, n)), sin_i = safe_sqrt(1.0f - cos_i * cos_i);
    float sin_q, cos_q;
    subtract_clamped(sin_i, cos_i, sin_b, cos_b, sin_q, cos_q);
    importance *= cos_q;
  }
  return importance;
}

}  // namespace caustica
