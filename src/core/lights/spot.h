// Mitsuba's `spot`: a point light (core/lights/point.h) with a profile of full intensity within
// beam_width of the axis, falling off linearly in the angle (as Mitsuba 3 does) to zero at
// cutoff_angle.
#pragma once
#include <memory>
#include "core/math.h"
#include "core/params.h"

namespace caustica {

class Light;

// position, direction or target, intensity, cutoff_angle, beam_width: a PointLight with a profile.
std::unique_ptr<Light> create_spot_light(const Params& p);

class SpotProfile {
 public:
  // Angles in degrees; beam_width is clamped to cutoff_angle.
  SpotProfile(const Vec3& direction, float cutoff_deg, float beam_deg);
  // The fraction of the intensity sent along the unit direction dir.
  float falloff(const Vec3& dir) const;
  // The integral of the falloff over the sphere (the light's power is intensity times it).
  float solid_angle() const { return solid_angle_; }
  float cos_cutoff() const { return cos_cutoff_; }
  const Frame& frame() const { return frame_; }

 private:
  Frame frame_;  // z along the axis
  float cutoff_, beam_, cos_cutoff_, cos_beam_;
  float solid_angle_ = 0;
};

}  // namespace caustica
