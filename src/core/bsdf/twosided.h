// Mitsuba's `twosided`: one BSDF on both sides, or a front and a back BSDF. The back one sees
// directions mirrored into its upper hemisphere.
#pragma once
#include "core/material.h"

namespace caustica {

class TwoSided final : public Material {
 public:
  TwoSided(const Material* front, const Material* back) : front_(front), back_(back) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override { return front_->flags() | back_->flags(); }
  float glossy_roughness() const override;
  Color albedo(const ShadingPoint& sp = {}) const override { return front_->albedo(sp); }

 private:
  const Material* front_;  // owned by the scene
  const Material* back_;
};

}  // namespace caustica
