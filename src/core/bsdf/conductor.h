// Metals: the smooth `conductor` (a perfect mirror when no index is given) and the microfacet
// `roughconductor`, with Fresnel reflectance from a complex index of refraction per channel.
#pragma once
#include "core/bsdf/microfacet.h"
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

// eta + i k relative to the outside medium, per RGB channel; k < 0 means "no Fresnel term"
// (Mitsuba's material "none": reflectance 1 at every angle).
struct ConductorIor {
  Color eta{0.0f}, k{-1.0f};
  bool perfect() const { return k.x < 0.0f; }
  Color reflectance(float cos_i) const;
};

class Conductor final : public SpecularBsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  // Our `mirror`: a perfect mirror tinted by reflectance.
  static std::unique_ptr<Bsdf> create_mirror(const Params& p);
  Conductor(const ConductorIor& ior, const ColorParam& specular_reflectance)
      : ior_(ior), specular_(specular_reflectance) {}
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override { return kBsdfSpecular | kBsdfReflection; }
  Color albedo(const ShadingPoint& sp = {}) const override { return specular_.at(sp) * ior_.reflectance(1.0f); }

 private:
  ConductorIor ior_;
  ColorParam specular_;
};

class RoughConductor final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  RoughConductor(const Roughness& rough, const ConductorIor& ior, const ColorParam& specular_reflectance)
      : rough_(rough), ior_(ior), specular_(specular_reflectance) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;  // the smooth limit
  uint32_t flags() const override { return kBsdfGlossy | kBsdfReflection; }
  float glossy_roughness() const override { return rough_.narrowest(); }
  Color albedo(const ShadingPoint& sp = {}) const override { return specular_.at(sp) * ior_.reflectance(1.0f); }

 private:
  Conductor smooth() const { return Conductor(ior_, specular_); }
  Roughness rough_;
  ConductorIor ior_;
  ColorParam specular_;
};

}  // namespace caustica
