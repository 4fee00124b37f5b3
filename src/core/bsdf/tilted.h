// What normalmap and bumpmap share: a nested BSDF seen in a shading frame tilted at each point.
// Directions are carried into that frame and back; as in Mitsuba, a direction on different
// sides of the two frames gets nothing, and the value keeps Mitsuba's f cos' (divided here by
// our frame's |cos|, which the integrators multiply back).
#pragma once
#include "core/bsdf/bsdf.h"

namespace caustica {

class TiltedFrameBsdf : public Bsdf {
 public:
  explicit TiltedFrameBsdf(const Bsdf* nested) : nested_(nested) {}
  Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const final;
  float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const final;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const final;
  int specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp = {}) const final;
  uint32_t flags() const final { return nested_->flags(); }
  // A tilted diffuse lobe is not albedo / pi in the surface's frame.
  bool is_lambertian() const final { return false; }
  bool diffuse_in_some_frame() const final { return nested_->is_lambertian(); }
  float glossy_roughness() const final { return nested_->glossy_roughness(); }
  Color albedo(const ShadingPoint& sp = {}) const final { return nested_->albedo(sp); }
  bool has_mask() const final { return nested_->has_mask(); }
  float refraction_eta(const Vec3& wo, const ShadingPoint& sp = {}) const final {
    return nested_->refraction_eta(frame_at(sp).to_local(wo), sp);
  }
  float opacity(const ShadingPoint& sp = {}) const final { return nested_->opacity(sp); }
  // The tilted frame at a shading point, in the local frame's coordinates.
  virtual Frame frame(const ShadingPoint& sp) const = 0;
  // frame(sp), computed once per shading point (ShadingPoint::tilted).
  const Frame& frame_at(const ShadingPoint& sp) const {
    if (sp.tilted_by != this) {
      sp.tilted = frame(sp);
      sp.tilted_by = this;
    }
    return sp.tilted;
  }

 protected:
  const Bsdf* nested_;  // owned by the scene
};

}  // namespace caustica
