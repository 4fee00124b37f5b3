// Mitsuba's `plastic` and `roughplastic`: a diffuse base under a dielectric coating. The coat
// reflects specularly (smooth) or by a microfacet lobe (rough); light that enters it reaches
// the base, scatters diffusely and leaves through the coat again, attenuated by the coat's
// transmittance on the way in and out and by the internal reflections between base and coat:
// f_d = (1 - F(cos_i)) (1 - F(cos_o)) rho / (pi eta^2 (1 - F_dr_int)) as in Mitsuba, written
// as rho / (pi (1 - F_dr_ext)), the same for a smooth coat; `nonlinear` replaces rho by
// rho (1 - F_dr_int) / (1 - rho F_dr_int) (Mitsuba's colour shift of repeated bounces). The
// rough coat's F is its directional albedo, tabulated at construction, and F_dr_ext its
// average (for sampling and albedo); the rough coat's diffuse term is Mitsuba's: its tabulated
// transmittance T(cos) on the way in and out, and its own internal F_dr_int (issue 24: the
// smooth coat's F_dr_int made rough plastic up to 27 % brighter than Mitsuba's).
#pragma once
#include <optional>
#include <vector>
#include "core/bsdf/microfacet.h"
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class Plastic final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  static std::unique_ptr<Bsdf> create_rough(const Params& p);
  // dist: the rough coat's microfacet distribution; none for a smooth coat.
  Plastic(const ColorParam& diffuse, const ColorParam& specular, float eta, bool nonlinear,
          std::optional<MicrofacetDistribution> dist);
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override;
  float glossy_roughness() const override { return dist_ ? std::min(dist_->alpha_u(), dist_->alpha_v()) : 0.0f; }
  Color albedo(const ShadingPoint& sp = {}) const override;

 private:
  // The coat's reflectance seen from a direction at cos theta (Fresnel, or the rough coat's
  // directional albedo), and the probability of sampling the coat there.
  float coat_reflectance(float cos_theta) const;
  float specular_probability(float cos_o, const ShadingPoint& sp) const;
  Color diffuse_eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const;
  Color coat_eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const;
  float coat_pdf(const Vec3& wo, const Vec3& wi) const;

  ColorParam diffuse_, specular_;
  float eta_;
  bool nonlinear_;
  std::optional<MicrofacetDistribution> dist_;
  float fdr_internal_ = 0;            // diffuse reflectance of the coat from inside
  float fdr_external_ = 0;            // and from outside (the smooth coat's only)
  CosineTable rough_albedo_;         // the rough coat's directional albedo over cos theta
  CosineTable rough_transmittance_;  // and its directional transmittance
};

}  // namespace caustica
