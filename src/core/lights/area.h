// Area lights: any emissive shape (triangles from a quad or mesh, or a sphere), sampled
// uniformly by area, emitting Le on the front side only. The scene reader makes one per object
// whose material has an emission.
#pragma once
#include <vector>
#include "core/lights/light.h"

namespace caustica {

class AreaLight final : public Light {
 public:
  AreaLight(std::vector<Primitive> shapes, const Color& radiance);
  bool sample_li(const Vec3& x, const Vec2& u, LightSample& s) const override;
  EmittedPhoton sample_emission(const Vec2& u_pos, const Vec2& u_dir) const override;
  Vec3 sample_origin(const Vec2& u, Vec3& normal, float& pdf) const override {
    pdf = 1.0f / area_;
    return sample_point(u, normal);
  }
  Color emitted_towards(const Vec3& normal, const Vec3& dir) const override {
    return radiance_ * std::max(0.0f, glm::dot(normal, dir));
  }
  Color power() const override { return kPi * area_ * radiance_; }
  bool is_delta() const override { return false; }
  Bounds bounds() const override;
  float pdf_li(const Vec3& x, const Vec3& y, const Vec3& ny) const override;
  float area() const { return area_; }
  Color surface_radiance() const override { return radiance_; }

 private:
  Vec3 sample_point(Vec2 u, Vec3& n) const;
  std::vector<Primitive> shapes_;
  Distribution1D by_area_;
  Color radiance_;
  float area_ = 0;
};

}  // namespace caustica
