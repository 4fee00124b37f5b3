// Mitsuba's `checkerboard`.
#include "core/textures/checkerboard.h"

namespace caustica {

std::unique_ptr<Texture> CheckerboardTexture::create(const Params& p) {
  return std::make_unique<CheckerboardTexture>(p.color("color0", Color(0.4f)), p.color("color1", Color(0.2f)),
                                               p.uv_transform("to_uv"));
}

Color CheckerboardTexture::eval(const TexturePoint& p) const {
  const Vec2 uv = to_uv_.apply(p.uv);
  const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
  return (u > 0.5f) == (v > 0.5f) ? c0_ : c1_;
}

}  // namespace caustica
