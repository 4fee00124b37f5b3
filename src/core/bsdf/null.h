// Mitsuba's `null`: a surface that is not there for light. Camera rays, shadow rays and photons
// pass straight through it (Scene::intersect skips it as it skips a fully transparent mask);
// Mitsuba uses it for the boundaries of participating media and for invisible shapes.
#pragma once
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"

namespace caustica {

class NullBsdf final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  // Nothing is ever scattered: a ray never stops at the surface.
  Color eval(const Vec3&, const Vec3&, const ShadingPoint& = {}) const override { return Color(0.0f); }
  float pdf(const Vec3&, const Vec3&, const ShadingPoint& = {}) const override { return 0.0f; }
  bool sample(const Vec3&, const Vec2&, float, BsdfSample&, const ShadingPoint& = {}) const override { return false; }
  uint32_t flags() const override { return 0; }
  Color albedo(const ShadingPoint& = {}) const override { return Color(0.0f); }
  bool has_mask() const override { return true; }
  float opacity(const ShadingPoint& = {}) const override { return 0.0f; }
};

}  // namespace caustica
