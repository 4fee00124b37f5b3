// Microfacet distributions (GGX and Beckmann, anisotropic) with Smith's masking and sampling
// of the visible normals (Heitz 2018 for GGX; the visible-slope CDF inverted by Newton's
// method for Beckmann, after Jakob's derivation used in Mitsuba and pbrt-v3).
#pragma once
#include "core/math.h"

namespace caustica {

enum class MicrofacetType { GGX, Beckmann };

class MicrofacetDistribution {
 public:
  MicrofacetDistribution(MicrofacetType type, float alpha_u, float alpha_v);
  MicrofacetType type() const { return type_; }
  float alpha_u() const { return ax_; }
  float alpha_v() const { return ay_; }
  // Normal distribution D(m) for a microfacet normal m in the local frame (m.z > 0).
  float D(const Vec3& m) const;
  // Smith's Lambda(w); G1 = 1 / (1 + Lambda); G is the height-correlated form.
  float lambda(const Vec3& w) const;
  float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
  float G(const Vec3& wo, const Vec3& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }
  // A microfacet normal (m.z > 0) visible from wo, or from -wo when wo.z < 0, with density
  // pdf(wo, m).
  Vec3 sample_visible(const Vec3& wo, const Vec2& u) const;
  // Density of visible normals: G1(wo) |wo.m| D(m) / |wo.z|.
  float pdf(const Vec3& wo, const Vec3& m) const;

 private:
  Vec2 sample_beckmann_slopes(float cos_theta, const Vec2& u) const;
  MicrofacetType type_;
  float ax_, ay_;
};

// Mitsuba's roughness parameters are alphas, clamped away from 0 for numerical stability.
inline float clamp_alpha(float a) { return std::max(a, 1e-4f); }

}  // namespace caustica
