// Point lights.
#include "core/lights/point.h"
#include "core/lights/read.h"

namespace caustica {

bool PointLight::sample_li(const Vec3& x, const Vec2&, LightSample& s) const {
  const Vec3 d = position_ - x;
  const float dist2 = glm::dot(d, d);
  if (dist2 <= 0.0f) return false;
  s.p = position_;
  s.n = Vec3(0.0f);
  s.dist = std::sqrt(dist2);
  s.wi = d / s.dist;
  s.weight = intensity_ * (falloff(-s.wi) / dist2);
  s.pdf = 0.0f;
  return !is_black(s.weight);
}

EmittedPhoton PointLight::sample_emission(const Vec2&, const Vec2& u_dir) const {
  if (!profile_) return {position_, Vec3(0.0f), sample_uniform_sphere(u_dir), power()};
  // Within the profile: flux = I profile / pdf.
  float pdf = 0.0f;
  const Vec3 dir = profile_->sample(u_dir, pdf);
  return {position_, Vec3(0.0f), dir, pdf > 0.0f ? intensity_ * falloff(dir) / pdf : Color(0.0f)};
}

LightBounds PointLight::light_bounds() const {
  LightBounds b = Light::light_bounds();
  if (profile_) {
    b.normals = profile_->cone();
    if (b.normals.cos_theta > -1.0f) b.cos_theta_e = 1.0f;
  }
  return b;
}

Bounds PointLight::bounds() const {
  Bounds b;
  b.extend(position_);
  return b;
}

std::unique_ptr<Light> PointLight::create(const Params& p) {
  return std::make_unique<PointLight>(p.point("position"), read_nonzero(p, "intensity"));
}

}  // namespace caustica
