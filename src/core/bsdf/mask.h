// Mitsuba's `mask`: a BSDF made partly transparent by an opacity (a number or a texture: leaves,
// fences). Rays pass through where it is transparent: camera rays, shadow rays and photons
// alike, since Scene::intersect skips a masked hit with probability 1 - opacity; where a ray
// stops, the nested BSDF scatters it.
#pragma once
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class Mask final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  Mask(const Bsdf* nested, const ColorParam& opacity) : nested_(nested), opacity_(opacity) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override { return nested_->eval(wo, wi, sp); }
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override { return nested_->pdf(wo, wi, sp); }
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override {
    return nested_->sample(wo, u, u_lobe, s, sp);
  }
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override {
    return nested_->specular_lobes(wo, out, sp);
  }
  uint32_t flags() const override { return nested_->flags(); }
  float glossy_roughness() const override { return nested_->glossy_roughness(); }
  Color albedo(const ShadingPoint& sp = {}) const override { return nested_->albedo(sp); }
  bool has_mask() const override { return true; }
  float refraction_eta(const Vec3& wo, const ShadingPoint& sp = {}) const override { return nested_->refraction_eta(wo, sp); }
  // A masked null surface (or mask) lets through what either lets through.
  float opacity(const ShadingPoint& sp = {}) const override {
    return std::clamp(average(opacity_.at(sp)), 0.0f, 1.0f) * nested_->opacity(sp);
  }

 private:
  const Bsdf* nested_;  // owned by the scene
  ColorParam opacity_;
};

}  // namespace caustica
