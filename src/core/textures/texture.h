// Textures: colours that vary over a surface's (u, v), with Mitsuba 3's conventions: (0, 0) is
// the image's top-left corner, `to_uv` transforms the coordinates before the lookup. One
// plugin per file pair in core/textures/, each listed once in core/textures/registry.cpp.
#pragma once
#include <cstdint>
#include "core/math.h"

namespace caustica {

// A 2-D affine map of texture coordinates: uv' = M uv + t.
struct UvTransform {
  float m00 = 1, m01 = 0, m10 = 0, m11 = 1, tx = 0, ty = 0;
  Vec2 apply(const Vec2& uv) const { return Vec2(m00 * uv.x + m01 * uv.y + tx, m10 * uv.x + m11 * uv.y + ty); }
};

struct MeshAttributes;

// Where a texture is looked up: the surface's (u, v) and, on a mesh that carries attributes
// (PLY colours and properties), the triangle and the point's barycentrics on it, for the
// mesh_attribute texture. A bare (u, v) converts to one.
struct TexturePoint {
  Vec2 uv{0.0f};
  const MeshAttributes* mesh = nullptr;  // the hit mesh's attributes, or none
  uint32_t triangle = 0;                 // the triangle's index in that mesh
  Vec3 bary{0.0f};                       // barycentrics of the point on the triangle
  TexturePoint() = default;
  TexturePoint(const Vec2& at) : uv(at) {}  // NOLINT: a (u, v) converts implicitly
};

class Texture {
 public:
  virtual ~Texture() = default;
  virtual Color eval(const TexturePoint& p) const = 0;
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
  Color at(const TexturePoint& p) const { return texture ? texture->eval(p) : value; }
  bool is_black() const { return !texture && caustica::is_black(value); }
};

}  // namespace caustica
