// Mitsuba's `spot`: a point light (core/lights/point.h) with a profile of full intensity within
// beam_width of the axis, falling off linearly in the angle (as Mitsuba 3 does) to zero at
// cutoff_angle, optionally times a texture projected onto the cone: u = 1/2 + x / (2 z tan
// cutoff), v = 1/2 + y / (2 z tan cutoff) in the spot's frame (x towards cross(up, axis), y up),
// as Mitsuba 3's spot maps its `texture`.
#pragma once
#include <memory>
#include "core/light_bounds.h"
#include "core/math.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class Light;

// position, direction or target, up, intensity, cutoff_angle, beam_width, texture: a PointLight
// with a spot profile.
std::unique_ptr<Light> create_spot_light(const Params& p);

// How a point light's intensity varies with direction: the factor (per colour) along a unit
// direction, its integral over the sphere (the light's power is intensity times it), and
// directions sampled within where it is non-zero.
class EmissionProfile {
 public:
  virtual ~EmissionProfile() = default;
  virtual Color value(const Vec3& dir) const = 0;
  virtual Color integral() const = 0;
  virtual Vec3 sample(const Vec2& u, float& pdf) const = 0;
  // The cone outside which value() is zero (every direction unless a profile says).
  virtual DirectionCone cone() const { return DirectionCone::everywhere(); }
};

// An orthonormal frame with z along `axis` and x along cross(up, axis) (Mitsuba's camera-like
// emitters: x is "left", y up); `up` parallel to the axis falls back to any perpendicular one.
Frame oriented_frame(const Vec3& axis, const Vec3& up);

class SpotProfile final : public EmissionProfile {
 public:
  // Angles in degrees; beam_width is clamped to cutoff_angle.
  SpotProfile(const Vec3& direction, float cutoff_deg, float beam_deg, const Vec3& up = Vec3(0, 1, 0),
              const Texture* texture = nullptr);
  // The fraction of the intensity sent along the unit direction dir (without the texture).
  float falloff(const Vec3& dir) const;
  Color value(const Vec3& dir) const override;
  Color integral() const override { return integral_; }
  Vec3 sample(const Vec2& u, float& pdf) const override;
  float cos_cutoff() const { return cos_cutoff_; }
  DirectionCone cone() const override;
  const Frame& frame() const { return frame_; }

 private:
  Frame frame_;  // z along the axis
  float cutoff_, beam_, cos_cutoff_, cos_beam_;
  const Texture* texture_;  // owned by the scene, or null
  Color integral_{0.0f};
};

}  // namespace caustica
