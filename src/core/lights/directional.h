// Mitsuba's `directional`: parallel light of a given irradiance (on a surface facing it),
// travelling along `direction`. Its photons leave a disc outside the scene's bounding sphere.
#pragma once
#include <memory>
#include "core/lights/light.h"
#include "core/params.h"

namespace caustica {

class DirectionalLight final : public InfiniteLight {
 public:
  DirectionalLight(const Vec3& direction, const Color& irradiance)
      : dir_(glm::normalize(direction)), irradiance_(irradiance) {}
  // direction, irradiance.
  static std::unique_ptr<Light> create(const Params& p);
  bool sample_li(const Vec3& x, const Vec2& u, LightSample& s) const override;
  EmittedPhoton sample_emission(const Vec2& u_pos, const Vec2& u_dir) const override;
  LightPoint sample_origin(const Vec2& u) const override;
  Color emitted_towards(const LightPoint&, const Vec3&) const override { return Color(0.0f); }
  Color power() const override { return irradiance_ * (kPi * radius_ * radius_); }
  bool is_delta() const override { return true; }
  bool sample_travel(const Vec2&, Vec3& dir, Color& value) const override {
    dir = dir_;
    value = irradiance_;
    return true;
  }

 private:
  Vec3 dir_;
  Color irradiance_;
};

}  // namespace caustica
