// Mitsuba's `normalmap`: a nested BSDF seen in a shading frame tilted by a tangent-space normal
// texture, n' = normalize(2 rgb - 1) in the surface's (dp/du, n x dp/du, n) frame, s' = dp/du
// made perpendicular to n' (see tilted.h for how directions go through the frame).
#pragma once
#include <memory>
#include "core/bsdf/tilted.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class NormalMap final : public TiltedFrameBsdf {
 public:
  static std::unique_ptr<Bsdf> create(const Params& p);
  NormalMap(const Bsdf* nested, const ColorParam& normals) : TiltedFrameBsdf(nested), normals_(normals) {}
  Frame frame(const ShadingPoint& sp) const override;

 private:
  ColorParam normals_;
};

}  // namespace caustica
