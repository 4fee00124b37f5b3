// Where a light's emission can reach and how strongly: a box around its emitting points, a cone
// around their normals (or a spot's axis), and its power. The spatial light sampler
// (core/light_sampler.h) builds a tree of these and weighs each subtree by its importance at a
// shading point, as pbrt-v4's LightBounds and BVHLightSampler (Conty Estevez and Kulla 2018).
#pragma once
#include <algorithm>
#include <cmath>
#include "core/shape.h"

namespace caustica {

// A cone of directions around a unit axis with half-angle acos(cos_theta) (-1: every direction).
struct DirectionCone {
  Vec3 axis{0.0f, 0.0f, 1.0f};
  float cos_theta = -1.0f;
  static DirectionCone everywhere() { return {}; }
  // The smallest cone that holds both (exact for two cones; for many, a bound).
  static DirectionCone unite(const DirectionCone& a, const DirectionCone& b);
};

struct LightBounds {
  Bounds bounds;       // the emitting points (a point light's position)
  DirectionCone normals;  // their normals (a spot's or projector's axis and half-angle)
  // How far past a normal light still leaves: pi/2 (cos 0) for a surface emitting by cosine,
  // 0 (cos 1) for a spot that sends nothing outside its cone.
  float cos_theta_e = 0.0f;
  float phi = 0.0f;  // power (luminance-like scalar) times the light's sampling weight

  static LightBounds unite(const LightBounds& a, const LightBounds& b);
};

// The same bounds as their importance reads them (every shadow ray evaluates a few): the box's
// centre and half-diagonal, the cone's sine and cosine.
struct CompactLightBounds {
  Vec3 centre{0.0f};
  float r2 = 0.0f, r = 0.0f;  // the half-diagonal, squared and not
  Vec3 axis{0.0f, 0.0f, 1.0f};
  float cos_o = -1.0f, sin_o = 0.0f, cos_e = 0.0f, phi = 0.0f;
  CompactLightBounds() = default;
  explicit CompactLightBounds(const LightBounds& b);
  // An estimate of the light reaching p, a point with normal n (zero: no normal), from anything
  // these bounds hold: phi over the squared distance, times the cosine of the least angle
  // between the emitting cone and p's direction and, with a normal, of the least angle of
  // incidence. Zero only where no point and direction of the bounds can light p. One division
  // and one square root where the bounds are a point or emit every way (more only where a cone
  // or the normal needs the angle subtracted).
  float importance(const Vec3& p, const Vec3& n) const {
    const Vec3 d = p - centre;
    const float d2 = glm::dot(d, d);
    // Within the bounding sphere the bounds may lie in any direction: every cosine is 1, and the
    // distance is the radius (else a point at the centre would have infinite importance).
    if (d2 <= r2) return phi / std::max(r2, 1e-12f);
    const float inv_d2 = 1.0f / d2, inv_d = std::sqrt(inv_d2);
    const Vec3 wi = d * inv_d;  // from the light to p
    // The angle theta_b the bounds subtend at p: sin_b = r / d (its cosine when needed).
    const float sin_b = r * inv_d, cos2_b = 1.0f - r2 * inv_d2;
    // cos of max(0, angle(axis, wi) - theta_o - theta_b).
    float cos_p = 1.0f;
    const float cos_w = glm::dot(axis, wi);
    if (cos_w < cos_o) {
      const float sin_w = std::sqrt(std::max(0.0f, 1.0f - cos_w * cos_w));
      const float cos_x = cos_w * cos_o + sin_w * sin_o, sin_x = sin_w * cos_o - cos_w * sin_o;
      if (cos_x < 0.0f || cos_x * cos_x < cos2_b) {
        cos_p = cos_x * std::sqrt(std::max(0.0f, cos2_b)) + sin_x * sin_b;
      }
    }
    if (cos_p < cos_e) return 0.0f;
    // A spot's cone (cos_e 1) sends its intensity undiminished within it.
    float importance = phi * inv_d2 * (cos_e >= 1.0f ? 1.0f : std::max(cos_p, 0.0f));
    if (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f) {
      // cos of max(0, the angle of incidence (either side: surfaces may transmit) - theta_b).
      const float cos_i = std::abs(glm::dot(wi, n));
      if (cos_i * cos_i < cos2_b) {
        importance *= sin_b > 0.0f ? cos_i * std::sqrt(std::max(0.0f, cos2_b)) +
                                         std::sqrt(std::max(0.0f, 1.0f - cos_i * cos_i)) * sin_b
                                   : cos_i;
      }
    }
    return importance;
  }
};

}  // namespace caustica
