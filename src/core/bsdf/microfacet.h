// Microfacet distributions (GGX and Beckmann, anisotropic) with Smith's masking and sampling
// of the visible normals (Heitz 2018 for GGX; the visible-slope CDF inverted by Newton's
// method for Beckmann, after Jakob's derivation used in Mitsuba and pbrt-v3).
#pragma once
#include <algorithm>
#include <utility>
#include <vector>
#include "core/math.h"
#include "core/textures/texture.h"

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

// Solid-angle density of wi when a microfacet normal visible from wo is sampled and wo reflected
// about it; two-sided (both directions on either side of the surface), 0 across it.
float reflection_pdf(const MicrofacetDistribution& dist, const Vec3& wo, const Vec3& wi);

// A rough dielectric boundary's directional reflectance and transmittance (fractions of
// energy, single scattering: their sum falls below 1 as the surface gets rougher) for light
// arriving at cos theta from the side where the relative index is eta.
std::pair<double, double> rough_boundary(const MicrofacetDistribution& dist, float cos_theta, float eta);

// A function of cos theta tabulated at kSize + 1 equal steps over [0, 1], read linearly.
struct CosineTable {
  static constexpr int kSize = 64;
  std::vector<float> v;
  float operator()(float cos_theta) const {
    const float x = std::clamp(cos_theta, 0.0f, 1.0f) * kSize;
    const int i = std::min(int(x), kSize - 1);
    const float t = x - float(i);
    return (1.0f - t) * v[size_t(i)] + t * v[size_t(i) + 1];
  }
};

// A microfacet distribution whose alphas may vary over the surface (Mitsuba's alpha, alpha_u,
// alpha_v as textures: a colour texture's luminance), clamped by clamp_alpha.
class Roughness {
 public:
  Roughness(const MicrofacetDistribution& d) : fixed_(d) {}  // NOLINT: constant alphas convert implicitly
  Roughness(MicrofacetType type, const ColorParam& alpha_u, const ColorParam& alpha_v);
  MicrofacetDistribution at(const TexturePoint& uv) const;
  bool textured() const { return textured_; }
  // The narrower alpha where they are constant; 0 (the narrow case) where a texture may make
  // them anything.
  float narrowest() const { return textured_ ? 0.0f : std::min(fixed_.alpha_u(), fixed_.alpha_v()); }

 private:
  MicrofacetDistribution fixed_;
  ColorParam alpha_u_, alpha_v_;
  bool textured_ = false;
};

// Mitsuba's roughness parameters are alphas, clamped away from 0 for numerical stability.
inline float clamp_alpha(float a) { return std::max(a, 1e-4f); }

}  // namespace caustica
