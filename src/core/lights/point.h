// Mitsuba's `point`: a point light of a given intensity, uniform in every direction or shaped by
// an emission profile (the `spot` and `projector` plugins, core/lights/spot.h and projector.h,
// make it with one).
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
  PointLight(const Vec3& position, const Color& intensity, std::shared_ptr<const EmissionProfile> profile)
      : position_(position), intensity_(intensity), profile_(std::move(profile)) {}
  // position, intensity.
  static std::unique_ptr<Light> create(const Params& p);
  bool sample_li(const Vec3& x, const Vec2& u, LightSample& s) const override;
  EmittedPhoton sample_emission(const Vec2& u_pos, const Vec2& u_dir) const override;
  LightPoint sample_origin(const Vec2&) const override { return {position_, Vec3(0.0f), 1.0f, Vec2(0.0f)}; }
  Color emitted_towards(const LightPoint&, const Vec3& dir) const override { return intensity_ * falloff(dir); }
  Color power() const override { return intensity_ * (profile_ ? profile_->integral() : Color(4.0f * kPi)); }
  bool is_delta() const override { return true; }
  Bounds bounds() const override;
  // A profile's cone, within which it sends its intensity (cos_theta_e 1: nothing outside).
  LightBounds light_bounds() const override;

 private:
  Color falloff(const Vec3& dir) const { return profile_ ? profile_->value(dir) : Color(1.0f); }
  Vec3 position_;
  Color intensity_;
  std::shared_ptr<const EmissionProfile> profile_;
};

}  // namespace caustica
