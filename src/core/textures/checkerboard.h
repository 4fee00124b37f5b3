// Mitsuba's `checkerboard`: color0 where (u mod 1 > 1/2) == (v mod 1 > 1/2), color1 elsewhere.
#pragma once
#include <memory>
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class CheckerboardTexture final : public Texture {
 public:
  CheckerboardTexture(const Color& c0, const Color& c1, const UvTransform& to_uv) : c0_(c0), c1_(c1), to_uv_(to_uv) {}
  static std::unique_ptr<Texture> create(const Params& p);
  Color eval(const TexturePoint& p) const override;

 private:
  Color c0_, c1_;
  UvTransform to_uv_;
};

}  // namespace caustica
