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

Vec3 DirectionalLight::sample_origin(const Vec2& u, Vec3& normal, float& pdf) const {
  normal = Vec3(0.0f);
  pdf = 1.0f / (kPi * radius_ * radius_);
  return point_on_disc(centre_ - dir_ * (1.001f * radius_), dir_, radius_, u);
}

EmittedPhoton DirectionalLight::sample_emission(const Vec2& u_pos, const Vec2&) const {
  Vec3 normal;
  float pdf;
  const Vec3 origin = sample_origin(u_pos, normal, pdf);
  return {origin, normal, dir_, irradiance_ / pdf};
}

std::unique_ptr<Light> DirectionalLight::create(const Params& p) {
  return std::make_unique<DirectionalLight>(read_direction(p, "direction"), read_nonzero(p, "irradiance"));
}

}  // namespace caustica
