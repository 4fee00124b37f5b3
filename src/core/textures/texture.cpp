// Procedural textures.
#include "core/textures/texture.h"

namespace caustica {

Color CheckerboardTexture::eval(const Vec2& uv_in) const {
  const Vec2 uv = to_uv_.apply(uv_in);
  const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
  return (u > 0.5f) == (v > 0.5f) ? c0_ : c1_;
}

}  // namespace caustica
