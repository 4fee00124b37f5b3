// Mitsuba 0.6's `coating` and `roughcoating`: a nested BSDF under a dielectric layer of a given
// thickness and absorption. The layer's surface reflects (a mirror, or a microfacet lobe for the
// rough one); light that crosses it is refracted (Snell's law, flat), absorbed by
// exp(-sigma_a thickness (1 / |cos_in| + 1 / |cos_out|)) along the refracted directions, seen by
// the nested BSDF, and leaves again, weighted by the surface's transmittance on the way in and
// out (1 - Fresnel, or the rough surface's directional transmittance, tabulated) and compressed
// by 1 / eta^2 into the narrower cone inside. As in Mitsuba, light reflected back inside the
// layer is dropped. Sampling chooses the surface or the nested BSDF as Mitsuba does (by the
// surface's reflectance against the layer's transmittance); unlike Mitsuba 0.6's roughcoating,
// a delta lobe of the nested BSDF keeps its full weight.
#pragma once
#include <memory>
#include <optional>
#include "core/bsdf/bsdf.h"
#include "core/bsdf/microfacet.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class Coating final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  static std::unique_ptr<Bsdf> create_rough(const Params& p);
  // dist: the rough surface's microfacet distribution; none for a smooth one.
  Coating(const Bsdf* nested, float eta, float thickness, const ColorParam& sigma_a, const ColorParam& specular,
          std::optional<MicrofacetDistribution> dist);
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override;
  float glossy_roughness() const override;
  Color albedo(const ShadingPoint& sp = {}) const override;
  bool is_lambertian() const override { return false; }
  // A refracting base's index ratio; the layer's own is left out (an approximation: coated
  // glass is not in any scene we know).
  float refraction_eta(const Vec3& wo, const ShadingPoint& sp = {}) const override { return nested_->refraction_eta(wo, sp); }

 private:
  // w refracted into the layer on its own side (Snell's law); false under total internal
  // reflection (from inside out).
  bool refract_in(const Vec3& w, Vec3& inside) const;
  bool refract_out(const Vec3& inside, Vec3& w) const;
  // The surface's transmittance for light at |cos theta| outside: 1 - Fresnel, or the rough
  // surface's directional transmittance.
  float transmittance(float cos_theta) const;
  // The probability of sampling the surface rather than the nested BSDF, seen from wo.
  float surface_probability(float cos_o) const;
  Color absorption(const Vec3& a, const Vec3& b, const ShadingPoint& sp) const;
  Color surface_eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const;
  float surface_pdf(const Vec3& wo, const Vec3& wi) const;

  const Bsdf* nested_;  // owned by the scene
  float eta_, thickness_;
  ColorParam sigma_a_, specular_;
  std::optional<MicrofacetDistribution> dist_;
  float layer_weight_ = 0.5f;        // Mitsuba's 1 / (1 + mean exp(-2 thickness sigma_a))
  CosineTable rough_transmittance_;  // the rough surface's T(cos theta)
};

}  // namespace caustica
