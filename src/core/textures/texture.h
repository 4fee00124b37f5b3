// Textures: colours that vary over a surface's (u, v), with Mitsuba 3's conventions: (0, 0) is
// the image's top-left corner, `to_uv` transforms the coordinates before the lookup.
#pragma once
#include "core/math.h"

namespace caustica {

// A 2-D affine map of texture coordinates: uv' = M uv + t.
struct UvTransform {
  float m00 = 1, m01 = 0, m10 = 0, m11 = 1, tx = 0, ty = 0;
  Vec2 apply(const Vec2& uv) const { return Vec2(m00 * uv.x + m01 * uv.y + tx, m10 * uv.x + m11 * uv.y + ty); }
};

class Texture {
 public:
  virtual ~Texture() = default;
  virtual Color eval(const Vec2& uv) const = 0;
};

// Mitsuba's `checkerboard`: color0 where (u mod 1 > 1/2) == (v mod 1 > 1/2), color1 elsewhere.
class CheckerboardTexture final : public Texture {
 public:
  CheckerboardTexture(const Color& c0, const Color& c1, const UvTransform& to_uv) : c0_(c0), c1_(c1), to_uv_(to_uv) {}
  Color eval(const Vec2& uv) const override;

 private:
  Color c0_, c1_;
  UvTransform to_uv_;
};

// A colour parameter of a BSDF: a constant, or a texture owned by the scene.
struct ColorParam {
  Color value{0.0f};
  const Texture* texture = nullptr;
  ColorParam() = default;
  ColorParam(const Color& c) : value(c) {}  // NOLINT: a constant converts implicitly
  explicit ColorParam(const Texture* t) : texture(t) {}
  Color at(const Vec2& uv) const { return texture ? texture->eval(uv) : value; }
  bool is_black() const { return !texture && caustica::is_black(value); }
};

}  // namespace caustica
