// Textures: colours that vary over a surface's (u, v), with Mitsuba 3's conventions: (0, 0) is
// the image's top-left corner, `to_uv` transforms the coordinates before the lookup. One
// plugin per file pair in core/textures/, each listed once in core/textures/registry.cpp.
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
  // The colour channels the texture holds (a grey image: 1).
  virtual int channels() const { return 3; }
  // The gradient of the texture's scalar value (a colour's luminance, as Mitsuba's eval_1) with
  // respect to u and v, for bump mapping; false for a texture that has none to give.
  virtual bool gradient(const Vec2& /*uv*/, Vec2& /*grad*/) const { return false; }
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
