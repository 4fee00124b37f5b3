// Mitsuba 3's `projector`: a pinhole that projects an image, as a perspective camera with the
// same frame would see it. Along a direction at angle theta to the axis whose image point is
// (u, v), the intensity is pi scale E(u, v) / cos^3 theta, so that a plane perpendicular to the
// axis at distance 1 receives irradiance pi scale E (a white diffuse plane there shows radiance
// scale E, Mitsuba's normalisation). Photons leave uniformly over the image.
#pragma once
#include <memory>
#include "core/lights/spot.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class Light;

// position, direction or target, up, fov, fov_axis, irradiance (a texture or a colour), scale.
std::unique_ptr<Light> create_projector_light(const Params& p);

class ProjectorProfile final : public EmissionProfile {
 public:
  // tan_half_x: the tangent of half the horizontal field of view; aspect: the image's width
  // over its height.
  ProjectorProfile(const Frame& frame, float tan_half_x, float aspect, const ColorParam& image, float scale);
  Color value(const Vec3& dir) const override;
  Color integral() const override { return integral_; }
  Vec3 sample(const Vec2& u, float& pdf) const override;
  DirectionCone cone() const override;

 private:
  Frame frame_;  // z along the axis, x to the image's left, y up
  float tan_half_x_, aspect_, scale_;
  ColorParam image_;
  float area_;  // of the image on the plane at distance 1
  Color integral_{0.0f};
};

}  // namespace caustica
