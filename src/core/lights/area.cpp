// Area lights.
#include "core/lights/area.h"

namespace caustica {

AreaLight::AreaLight(std::vector<Primitive> shapes, const ColorParam& radiance,
                     const std::vector<TriangleAttributes>& attributes)
    : shapes_(std::move(shapes)), radiance_(radiance), mean_radiance_(radiance.value) {
  std::vector<float> areas;
  for (const Primitive& p : shapes_) {
    areas.push_back(p.area());
    area_ += areas.back();
  }
  by_area_ = Distribution1D(areas.data(), areas.size());
  if (!radiance_.texture) return;
  uvs_.resize(shapes_.size());
  for (size_t i = 0; i < shapes_.size(); ++i) {
    if (shapes_[i].attributes < attributes.size()) uvs_[i] = attributes[shapes_[i].attributes];
  }
  // The texture's mean over the surface, for the light's power (which lights are chosen by):
  // a 128 x 128 stratified grid of points by area. An estimate; the images do not depend on
  // it, only how samples are shared between lights.
  constexpr int kGrid = 128;
  glm::dvec3 sum(0.0);
  for (int j = 0; j < kGrid; ++j) {
    for (int i = 0; i < kGrid; ++i) {
      Vec3 n;
      TexturePoint uv;
      sample_point(Vec2((float(i) + 0.5f) / kGrid, (float(j) + 0.5f) / kGrid), n, uv);
      sum += glm::dvec3(radiance_.at(uv));
    }
  }
  mean_radiance_ = Color(sum / double(kGrid * kGrid));
}

Vec3 AreaLight::sample_point(Vec2 u, Vec3& n, TexturePoint& at) const {
  const size_t i = by_area_.sample_remap(u.x);
  const Vec3 p = shapes_[i].sample_point(u, &n);
  at = radiance_.texture ? surface_point(shapes_[i], &uvs_[i], p) : TexturePoint();
  return p;
}

LightPoint AreaLight::sample_origin(const Vec2& u) const {
  LightPoint o;
  o.p = sample_point(u, o.n, o.at);
  o.pdf = 1.0f / area_;
  return o;
}

bool AreaLight::sample_li(const Vec3& x, const Vec2& u, LightSample& s) const {
  TexturePoint uv;
  s.p = sample_point(u, s.n, uv);
  const Vec3 d = s.p - x;
  const float dist2 = glm::dot(d, d);
  if (dist2 <= 0.0f) return false;
  s.dist = std::sqrt(dist2);
  s.wi = d / s.dist;
  const float cos_l = -glm::dot(s.n, s.wi);
  if (cos_l <= 0.0f) return false;  // back side: no emission
  s.weight = radiance_.at(uv) * (cos_l * area_ / dist2);  // pdf_A = 1 / area
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
  TexturePoint uv;
  e.origin = sample_point(u_pos, e.normal, uv);
  e.dir = Frame(e.normal).to_world(sample_cosine_hemisphere(u_dir));
  e.flux = kPi * area_ * radiance_.at(uv);  // Le cos / ((1/A) (cos/pi))
  return e;
}

LightBounds AreaLight::light_bounds() const {
  LightBounds b = Light::light_bounds();
  bool first = true;
  for (const Primitive& p : shapes_) {
    if (p.kind != ShapeKind::Triangle) return b;  // a sphere emits every way
    const DirectionCone c{p.normal_at(p.p0), 1.0f};
    b.normals = first ? c : DirectionCone::unite(b.normals, c);
    first = false;
    if (b.normals.cos_theta <= -1.0f) break;
  }
  return b;
}

Bounds AreaLight::bounds() const {
  Bounds b;
  for (const Primitive& p : shapes_) b.extend(p.bounds());
  return b;
}

}  // namespace caustica
