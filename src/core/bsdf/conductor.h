// Metals: the smooth `conductor` (a perfect mirror when no index is given) and the microfacet
// `roughconductor`, with Fresnel reflectance from a complex index of refraction per channel.
#pragma once
#include "core/bsdf/microfacet.h"
#include "core/material.h"

namespace caustica {

// eta + i k relative to the outside medium, per RGB channel; k < 0 means "no Fresnel term"
// (Mitsuba's material "none": reflectance 1 at every angle).
struct ConductorIor {
  Color eta{0.0f}, k{-1.0f};
  bool perfect() const { return k.x < 0.0f; }
  Color reflectance(float cos_i) const;
};

class Conductor final : public SpecularMaterial {
 public:
  Conductor(const ConductorIor& ior, const Color& specular_reflectance)
      : ior_(ior), specular_(specular_reflectance) {}
  int specular_lobes(const Vec3& wo, BsdfSample* out) const override;
  uint32_t flags() const override { return kBsdfSpecular | kBsdfReflection; }
  Color albedo() const override { return specular_ * ior_.reflectance(1.0f); }

 private:
  ConductorIor ior_;
  Color specular_;
};

class RoughConductor final : public Material {
 public:
  RoughConductor(const MicrofacetDistribution& dist, const ConductorIor& ior, const Color& specular_reflectance)
      : dist_(dist), ior_(ior), specular_(specular_reflectance) {}
  Color eval(const Vec3& wo, const Vec3& wi) const override;
  float pdf(const Vec3& wo, const Vec3& wi) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s) const override;
  int specular_lobes(const Vec3& wo, BsdfSample* out) const override;  // the smooth limit
  uint32_t flags() const override { return kBsdfGlossy | kBsdfReflection; }
  float glossy_roughness() const override { return std::min(dist_.alpha_u(), dist_.alpha_v()); }
  Color albedo() const override { return specular_ * ior_.reflectance(1.0f); }

 private:
  Conductor smooth() const { return Conductor(ior_, specular_); }
  MicrofacetDistribution dist_;
  ConductorIor ior_;
  Color specular_;
};

}  // namespace caustica
