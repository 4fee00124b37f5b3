// Mitsuba's `point`: a point light of a given intensity, uniform in every direction or shaped by
// a spot profile (the `spot` plugin, core/lights/spot.h, makes it with one).
#pragma once
#include <memory>
#include <optional>
#include "core/lights/light.h"
#include "core/lights/spot.h"
#include "core/params.h"

namespace caustica {

class PointLight final : public Light {
 public:
  PointLight(const Vec3& position, const Color& intensity) : position_(position), intensity_(intensity) {}
  PointLight(const Vec3& position, const Color& intensity, const SpotProfile& spot)
      : position_(position), intensity_(intensity), spot_(spot) {}
  // position, intensity.
  static std::unique_ptr<Light> create(const Params& p);
  bool sample_li(const Vec3& x, const Vec2& u, LightSample& s) const override;
  EmittedPhoton sample_emission(const Vec2& u_pos, const Vec2& u_dir) const override;
  LightPoint sample_origin(const Vec2&) const override { return {position_, Vec3(0.0f), 1.0f, Vec2(0.0f)}; }
  Color emitted_towards(const LightPoint&, const Vec3& dir) const override { return intensity_ * falloff(dir); }
  Color power() const override { return intensity_ * (spot_ ? spot_->solid_angle() : 4.0f * kPi); }
  bool is_delta() const override { return true; }
  Bounds bounds() const override;

 private:
  float falloff(const Vec3& dir) const { return spot_ ? spot_->falloff(dir) : 1.0f; }
  Vec3 position_;
  Color intensity_;
  std::optional<SpotProfile> spot_;
};

}  // namespace caustica
