// Mitsuba 3's `bumpmap`: a nested BSDF in the shading frame of a surface displaced along its
// normal by a height texture times `scale`. With g = scale (dh/du, dh/dv), the displaced
// surface's tangents are dp/du + g.u n and dp/dv + g.v n (their normal components replaced,
// as Mitsuba does), its normal their cross product turned to the surface's side, and s' = dp/du
// made perpendicular to it (Mitsuba 3 mixes world and local coordinates there; we do not: this
// only turns anisotropic nested BSDFs). Where the height's gradient is zero the frame is the
// surface's own, exactly. See tilted.h for how directions go through the frame.
#pragma once
#include <memory>
#include "core/bsdf/tilted.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class BumpMap final : public TiltedFrameBsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  // height: a texture with a gradient, or null for a constant height (no bump at all).
  BumpMap(const Bsdf* nested, const Texture* height, float scale) : TiltedFrameBsdf(nested), height_(height), scale_(scale) {}
  Frame frame(const ShadingPoint& sp) const override;

 private:
  const Texture* height_;
  float scale_;
};

}  // namespace caustica
