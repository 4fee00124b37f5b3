// Lambertian reflection (Mitsuba's `diffuse`), two-sided.
#pragma once
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class Lambertian final : public Bsdf {
 public:
  // Mitsuba's `diffuse`: reflectance (or its alias albedo), a colour or a texture.
  static std::unique_ptr<Bsdf> create(const Params& p);
  explicit Lambertian(const ColorParam& albedo) : albedo_(albedo) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;  // rho / pi on wo's side
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override { return kBsdfDiffuse | kBsdfReflection; }
  Color albedo(const ShadingPoint& sp = {}) const override { return albedo_.at(sp); }

 private:
  ColorParam albedo_;
};

// Caustica's reflecting BSDFs are two-sided: seen from below, they are evaluated mirrored
// into the upper hemisphere (Mitsuba's are black from below unless wrapped in `twosided`).
inline Vec3 flip_z(const Vec3& w) { return Vec3(w.x, w.y, -w.z); }

}  // namespace caustica
