// Mitsuba's `normalmap`: a nested BSDF seen in a shading frame tilted by a tangent-space normal
// texture, n' = normalize(2 rgb - 1) in the surface's (dp/du, n x dp/du, n) frame, s' = dp/du
// made perpendicular to n'. Directions are carried into that frame and back; as in Mitsuba, a
// direction on different sides of the two frames gets nothing, and the value keeps Mitsuba's
// f cos' (divided here by our frame's |cos|, which the integrators multiply back).
#pragma once
#include <memory>
#include "core/bsdf/bsdf.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class NormalMap final : public Bsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  NormalMap(const Bsdf* nested, const ColorParam& normals) : nested_(nested), normals_(normals) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const override;
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const override;
  uint32_t flags() const override { return nested_->flags(); }
  // A tilted diffuse lobe is not albedo / pi in the surface's frame.
  bool is_lambertian() const override { return false; }
  float glossy_roughness() const override { return nested_->glossy_roughness(); }
  Color albedo(const ShadingPoint& sp = {}) const override { return nested_->albedo(sp); }
  bool has_mask() const override { return nested_->has_mask(); }
  float opacity(const ShadingPoint& sp = {}) const override { return nested_->opacity(sp); }
  // The tilted frame at a shading point, in the local frame's coordinates.
  Frame frame(const ShadingPoint& sp) const;

 private:
  const Bsdf* nested_;  // owned by the scene
  ColorParam normals_;
};

}  // namespace caustica
