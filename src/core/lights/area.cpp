// Area lights.
#include "core/lights/area.h"

namespace caustica {

AreaLight::AreaLight(std::vector<Primitive> shapes, const Color& radiance)
    : shapes_(std::move(shapes)), radiance_(radiance) {
  std::vector<float> areas;
  for (const Primitive& p : shapes_) {
    areas.push_back(p.area());
    area_ += areas.back();
  }
  by_area_ = Distribution1D(areas.data(), areas.size());
}

Vec3 AreaLight::sample_point(Vec2 u, Vec3& n) const {
  const size_t i = by_area_.sample_remap(u.x);
  return shapes_[i].sample_point(u, &n);
}

bool AreaLight::sample_li(const Vec3& x, const Vec2& u, LightSample& s) const {
  s.p = sample_point(u, s.n);
  const Vec3 d = s.p - x;
  const float dist2 = glm::dot(d, d);
  if (dist2 <= 0.0f) return false;
  s.dist = std::sqrt(dist2);
  s.wi = d / s.dist;
  const float cos_l = -glm::dot(s.n, s.wi);
  if (cos_l <= 0.0f) return false;  // back side: no emission
  s.weight = radiance_ * (cos_l * area_ / dist2);  // pdf_A = 1 / area
  s.pdf = dist2 / (cos_l * area_);
  return true;
}

float AreaLight::pdf_li(const Vec3& x, const Vec3& y, const Vec3& ny) const {
  const Vec3 d = y - x;
  const float dist2 = glm::dot(d, d);
  const float cos_l = std::abs(glm::dot(ny, d)) / std::sqrt(dist2);
  return cos_l > 0.0f ? dist2 / (cos_l * area_) : 0.0f;
}

EmittedPhoton AreaLight::sample_emission(const Vec2& u_pos, const Vec2& u_dir) const {
  EmittedPhoton e;
  e.origin = sample_point(u_pos, e.normal);
  e.dir = Frame(e.normal).to_world(sample_cosine_hemisphere(u_dir));
  e.flux = power();  // Le cos / ((1/A) (cos/pi)) = pi A Le
  return e;
}

Bounds AreaLight::bounds() const {
  Bounds b;
  for (const Primitive& p : shapes_) b.extend(p.bounds());
  return b;
}

}  // namespace caustica
