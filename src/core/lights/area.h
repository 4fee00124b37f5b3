// Area lights: any emissive shape (triangles from a quad or mesh, or a sphere), sampled
// uniformly by area, emitting Le on the front side only; Le is a colour or a texture over the
// shape's UVs (Mitsuba's area emitter with a bitmap `radiance`). The scene reader makes one per
// object whose material has an emission.
#pragma once
#include <vector>
#include "core/lights/light.h"
#include "core/textures/texture.h"

namespace caustica {

class AreaLight final : public Light {
 public:
  // `attributes`: the scene's per-triangle UVs and mesh attributes, which a textured Le is
  // looked up with (the shapes' Primitive::attributes index them).
  AreaLight(std::vector<Primitive> shapes, const ColorParam& radiance,
            const std::vector<TriangleAttributes>& attributes = {});
  bool sample_li(const Vec3& x, const Vec2& u, LightSample& s) const override;
  EmittedPhoton sample_emission(const Vec2& u_pos, const Vec2& u_dir) const override;
  LightPoint sample_origin(const Vec2& u) const override;
  Color emitted_towards(const LightPoint& at, const Vec3& dir) const override {
    return radiance_.at(at.at) * std::max(0.0f, glm::dot(at.n, dir));
  }
  // pi A times Le averaged over the surface (by area, for a texture).
  Color power() const override { return kPi * area_ * mean_radiance_; }
  bool is_delta() const override { return false; }
  Bounds bounds() const override;
  // Its triangles' front-side normals in one cone (a sphere's: every direction).
  LightBounds light_bounds() const override;
  float pdf_li(const Vec3& x, const Vec3& y, const Vec3& ny) const override;
  float area() const { return area_; }
  Color surface_radiance(const TexturePoint& at = {}) const override { return radiance_.at(at); }
  bool textured() const { return radiance_.texture != nullptr; }

 private:
  // A point uniformly by area, with its normal and where its texture is looked up.
  Vec3 sample_point(Vec2 u, Vec3& n, TexturePoint& at) const;
  std::vector<Primitive> shapes_;
  std::vector<TriangleAttributes> uvs_;  // by shape, for a textured Le (else empty)
  Distribution1D by_area_;
  ColorParam radiance_;
  Color mean_radiance_{0.0f};
  float area_ = 0;
};

}  // namespace caustica
