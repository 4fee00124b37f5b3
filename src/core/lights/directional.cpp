// Directional light.
#include "core/lights/directional.h"
#include "core/lights/read.h"

namespace caustica {

bool DirectionalLight::sample_li(const Vec3& x, const Vec2&, LightSample& s) const {
  s.wi = -dir_;
  // A point beyond the scene's bounding sphere along the light.
  s.dist = 2.0f * (radius_ + glm::length(x - centre_));
  s.p = x + s.dist * s.wi;
  s.n = Vec3(0.0f);
  s.weight = irradiance_;
  s.pdf = 0.0f;
  return true;
}

LightPoint DirectionalLight::sample_origin(const Vec2& u) const {
  return {point_on_disc(centre_ - dir_ * (1.001f * radius_), dir_, radius_, u), Vec3(0.0f),
          1.0f / (kPi * radius_ * radius_), Vec2(0.0f)};
}

EmittedPhoton DirectionalLight::sample_emission(const Vec2& u_pos, const Vec2&) const {
  const LightPoint origin = sample_origin(u_pos);
  return {origin.p, origin.n, dir_, irradiance_ / origin.pdf};
}

std::unique_ptr<Light> DirectionalLight::create(const Params& p) {
  return std::make_unique<DirectionalLight>(read_direction(p, "direction"), read_nonzero(p, "irradiance"));
}

}  // namespace caustica
