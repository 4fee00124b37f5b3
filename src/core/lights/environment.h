// Environment lights: Mitsuba's `envmap` (a latitude-longitude image, importance-sampled by
// luminance times sin(theta)) and `constant` (uniform radiance, the same code with a flat
// image). Directions map to the image as in Mitsuba 3: u = atan2(x, -z) / 2 pi, v = acos(y) / pi
// in the light's frame (to_world). Radiance is piecewise constant over the pixels, so that
// sampling and evaluation agree exactly.
#pragma once
#include "core/image.h"
#include "core/lights/light.h"
#include "core/params.h"
#include "core/sampling.h"

namespace caustica {

class EnvironmentLight final : public InfiniteLight {
 public:
  // to_world: the light's rotation (columns: the local axes in world space).
  EnvironmentLight(Image image, float scale, const glm::mat3& to_world);
  static std::unique_ptr<EnvironmentLight> constant(const Color& radiance);
  // `envmap`: filename, scale, to_world.
  static std::unique_ptr<Light> create(const Params& p);
  // `constant`: radiance.
  static std::unique_ptr<Light> create_constant(const Params& p);

  bool sample_li(const Vec3& x, const Vec2& u, LightSample& s) const override;
  EmittedPhoton sample_emission(const Vec2& u_pos, const Vec2& u_dir) const override;
  LightPoint sample_origin(const Vec2& u) const override;
  Color emitted_towards(const LightPoint&, const Vec3&) const override { return Color(0.0f); }
  Color power() const override { return power_per_area_ * (kPi * radius_ * radius_); }
  bool is_delta() const override { return false; }
  Color escaped(const Vec3& dir) const override;
  float pdf_escaped(const Vec3& dir) const override;
  bool sample_travel(const Vec2& u, Vec3& dir, Color& value) const override;

  // A direction towards the environment and its solid-angle density.
  Vec3 sample_direction(const Vec2& u, float& pdf) const;

 private:
  Vec2 to_uv(const Vec3& world_dir) const;
  Vec3 from_uv(const Vec2& uv) const;
  Color lookup(const Vec2& uv) const;
  Image image_;
  glm::mat3 to_world_, to_local_;
  Distribution2D distribution_;
  Color power_per_area_{0.0f};  // integral of L over the sphere (radiant exitance of the disc)
};

}  // namespace caustica
