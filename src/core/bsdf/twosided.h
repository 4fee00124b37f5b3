// Mitsuba's `twosided`: one BSDF on both sides, or a front and a back BSDF. The back one sees
// directions mirrored into its upper hemisphere.
#pragma once
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"

namespace caustica {

class TwoSided final : public Bsdf {
 public:
  // One BSDF on both sides, or two: front and back.
  static std::unique_ptr<Bsdf> create(const Params& p);
  TwoSided(const Bsdf* front, const Bsdf* back) : front_(front), back_(back) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override { return front_->flags() | back_->flags(); }
  float glossy_roughness() const override { return narrowest_glossy(*front_, *back_); }
  Color albedo(const ShadingPoint& sp = {}) const override { return front_->albedo(sp); }
  Color null_transmission(const Vec3& wo, const ShadingPoint& sp = {}) const override;
  float refraction_eta(const Vec3& wo, const ShadingPoint& sp = {}) const override;
  // A two-sided mask or null surface lets rays through as its front does (opacity() does not
  // know the side a ray comes from; one BSDF on both sides is exact).
  bool has_mask() const override { return front_->has_mask() || back_->has_mask(); }
  float opacity(const ShadingPoint& sp = {}) const override { return front_->opacity(sp); }

 private:
  const Bsdf* front_;  // owned by the scene
  const Bsdf* back_;
};

}  // namespace caustica
