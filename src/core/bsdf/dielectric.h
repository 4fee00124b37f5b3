// Dielectrics: the smooth `dielectric` (our `glass`), `thindielectric` (a thin pane: no
// refraction, inter-reflections summed) and the microfacet `roughdielectric` (Walter et al.
// 2007). eta is the interior index over the exterior one; the normal points outside. Weights are
// the adjoint's (photons carry flux across unchanged); eye paths scale radiance that crosses
// the boundary by 1 / eta^2 (radiance_scale in bsdf.h).
#pragma once
#include "core/bsdf/fresnel.h"
#include "core/bsdf/microfacet.h"
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"

namespace caustica {

// What scales a dielectric's reflected and transmitted light (Mitsuba's specular_reflectance and
// specular_transmittance; 1 for physical glass).
struct DielectricTint {
  ColorParam reflect{Color(1.0f)}, transmit{Color(1.0f)};
  // The larger scale at uv: what a photon's Russian roulette takes as the surface's albedo.
  Color albedo(const TexturePoint& uv) const { return glm::max(reflect.at(uv), transmit.at(uv)); }
};

class Dielectric final : public SpecularBsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  // Our `glass`: one index `ior` and a choice of Fresnel model (exact or schlick).
  static std::unique_ptr<Bsdf> create_glass(const Params& p);
  Dielectric(float eta, FresnelModel model, const DielectricTint& tint = {}) : eta_(eta), model_(model), tint_(tint) {}
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override { return kBsdfSpecular | kBsdfReflection | kBsdfTransmission; }
  Color albedo(const ShadingPoint& sp = {}) const override { return tint_.albedo(sp); }
  // Reflectance for local direction wo (either side of the boundary).
  float reflectance(const Vec3& wo) const;
  // Refracted local direction for wo; false under total internal reflection.
  bool refract(const Vec3& wo, Vec3& wt) const;
  float eta() const { return eta_; }
  float refraction_eta(const Vec3& wo, const ShadingPoint& = {}) const override { return wo.z > 0.0f ? eta_ : 1.0f / eta_; }

 private:
  float eta_;
  FresnelModel model_;
  DielectricTint tint_;
};

class ThinDielectric final : public SpecularBsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  explicit ThinDielectric(float eta, const DielectricTint& tint = {}) : eta_(eta), tint_(tint) {}
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override { return kBsdfSpecular | kBsdfReflection | kBsdfTransmission | kBsdfNull; }
  Color albedo(const ShadingPoint& sp = {}) const override { return tint_.albedo(sp); }
  Color null_transmission(const Vec3& wo, const ShadingPoint& sp = {}) const override;
  // Reflectance of the pane with all internal reflections: R + T^2 R / (1 - R^2) = 2R / (1 + R).
  float reflectance(float cos_i) const;

 private:
  float eta_;
  DielectricTint tint_;
};

class RoughDielectric final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  RoughDielectric(const Roughness& rough, float eta, const DielectricTint& tint = {})
      : rough_(rough), eta_(eta), tint_(tint) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override {  // the smooth limit
    return Dielectric(eta_, FresnelModel::Exact, tint_).specular_lobes(wo, out, sp);
  }
  uint32_t flags() const override { return kBsdfGlossy | kBsdfReflection | kBsdfTransmission; }
  float glossy_roughness() const override { return rough_.narrowest(); }
  Color albedo(const ShadingPoint& sp = {}) const override { return tint_.albedo(sp); }
  float refraction_eta(const Vec3& wo, const ShadingPoint& = {}) const override { return wo.z > 0.0f ? eta_ : 1.0f / eta_; }

 private:
  // The half vector of (wo, wi), facing +z, and the relative index across it; false when the
  // pair cannot be connected by a microfacet.
  bool half_vector(const Vec3& wo, const Vec3& wi, Vec3& wm, float& etap) const;
  Roughness rough_;
  float eta_;
  DielectricTint tint_;
};

}  // namespace caustica
