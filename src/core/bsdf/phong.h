// The normalised modified Phong BRDF (Lafortune and Willems 1994; Mitsuba 0.6's `phong`):
// f = kd / pi + ks (n + 2) / (2 pi) cos^n(alpha), alpha between wi and wo's mirror direction.
#pragma once
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class Phong final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  Phong(const ColorParam& diffuse, const ColorParam& specular, float exponent);
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override;
  // The Beckmann alpha of equal highlight width, sqrt(2 / (n + 2)) (Walter et al. 2007, eq. 33).
  float glossy_roughness() const override { return std::sqrt(2.0f / (exponent_ + 2.0f)); }
  Color albedo(const ShadingPoint& sp = {}) const override { return kd_.at(sp) + ks_.at(sp); }

 private:
  float specular_probability(const ShadingPoint& sp) const;  // of sampling the specular lobe
  ColorParam kd_, ks_;
  float exponent_;
};

}  // namespace caustica
