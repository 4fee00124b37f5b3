// Mitsuba's `blendbsdf`: (1 - weight) times the first BSDF plus weight times the second, the
// weight a number or a texture in [0, 1] (a colour texture's luminance, as Mitsuba's eval_1).
// Sampling picks a component by the weight, then evaluates the mixture for non-delta directions.
#pragma once
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class BlendBsdf final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  BlendBsdf(const Bsdf* first, const Bsdf* second, const ColorParam& weight) : a_(first), b_(second), weight_(weight) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  // Both components' delta lobes, scaled by their weights; mirror reflections of both merge
  // into one. More than two distinct lobes (two dielectrics of different indices) give none.
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override { return a_->flags() | b_->flags(); }
  float glossy_roughness() const override { return narrowest_glossy(*a_, *b_); }
  Color albedo(const ShadingPoint& sp = {}) const override;
  // The refracting component's (the first's when both refract: blends of two indices are
  // approximated by it).
  float refraction_eta(const Vec3& wo, const ShadingPoint& sp = {}) const override {
    const float a = a_->refraction_eta(wo, sp);
    return a != 1.0f ? a : b_->refraction_eta(wo, sp);
  }
  // The weight at a shading point, in [0, 1].
  float weight(const ShadingPoint& sp) const;

 private:
  const Bsdf* a_;  // owned by the scene
  const Bsdf* b_;
  ColorParam weight_;
};

}  // namespace caustica
