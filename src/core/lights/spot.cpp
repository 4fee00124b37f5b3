// Spot lights.
#include "core/lights/spot.h"
#include "core/lights/point.h"
#include "core/lights/read.h"
#include "core/sampling.h"

namespace caustica {

Frame oriented_frame(const Vec3& axis, const Vec3& up) {
  const Vec3 z = glm::normalize(axis);
  const Vec3 x = glm::cross(up, z);
  const float len = glm::length(x);
  if (!(len > 1e-6f)) return Frame(z);
  Frame f;
  f.n = z;
  f.s = x / len;
  f.t = glm::cross(z, f.s);
  return f;
}

SpotProfile::SpotProfile(const Vec3& direction, float cutoff_deg, float beam_deg, const Vec3& up, const Texture* texture)
    : frame_(texture ? oriented_frame(direction, up) : Frame(glm::normalize(direction))), texture_(texture) {
  cutoff_ = cutoff_deg * kPi / 180.0f;
  beam_ = std::min(beam_deg, cutoff_deg) * kPi / 180.0f;
  cos_cutoff_ = std::cos(cutoff_);
  cos_beam_ = std::cos(beam_);
  if (!texture_) {
    // 2 pi [(1 - cos beam) + integral over the transition of falloff(theta) sin theta], the
    // transition by the midpoint rule.
    double sum = 1.0 - double(cos_beam_);
    const int steps = 4096;
    const double h = double(cutoff_ - beam_) / steps;
    for (int i = 0; i < steps && h > 0; ++i) {
      const double theta = double(beam_) + (i + 0.5) * h;
      sum += (double(cutoff_) - theta) / double(cutoff_ - beam_) * std::sin(theta) * h;
    }
    integral_ = Color(float(2.0 * 3.14159265358979323846 * sum));
    return;
  }
  // With a texture: the midpoint rule over the cone in (theta, phi).
  const int nt = 256, np = 256;
  glm::dvec3 sum(0.0);
  const double dt = double(cutoff_) / nt, dp = 2.0 * 3.14159265358979323846 / np;
  for (int i = 0; i < nt; ++i) {
    const double theta = (i + 0.5) * dt;
    for (int j = 0; j < np; ++j) {
      const double phi = (j + 0.5) * dp;
      const Vec3 local(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
      sum += glm::dvec3(value(frame_.to_world(local))) * (std::sin(theta) * dt * dp);
    }
  }
  integral_ = Color(sum);
}

DirectionCone SpotProfile::cone() const {
  return {frame_.n, std::cos(std::min(kPi, cutoff_ + 1e-3f))};  // a hair wider: rounding at the edge
}

float SpotProfile::falloff(const Vec3& dir) const {
  const float cos_t = glm::dot(dir, frame_.n);
  if (cos_t <= cos_cutoff_) return 0.0f;
  if (cos_t >= cos_beam_ || cutoff_ <= beam_) return 1.0f;
  return (cutoff_ - std::acos(std::min(1.0f, cos_t))) / (cutoff_ - beam_);
}

Color SpotProfile::value(const Vec3& dir) const {
  const float f = falloff(dir);
  if (!texture_ || f <= 0.0f) return Color(f);
  const Vec3 d = frame_.to_local(dir);
  const float k = 0.5f / (d.z * std::tan(cutoff_));
  return f * texture_->eval(Vec2(0.5f + d.x * k, 0.5f + d.y * k));
}

Vec3 SpotProfile::sample(const Vec2& u, float& pdf) const {
  pdf = uniform_cone_pdf(cos_cutoff_);
  return frame_.to_world(sample_uniform_cone(u, cos_cutoff_));
}

std::unique_ptr<Light> create_spot_light(const Params& p) {
  const Vec3 pos = p.point("position");
  const Vec3 dir = read_aim(p, pos);
  const float cutoff = float(p.number_in("cutoff_angle", 20.0, 0.01, 180.0));
  const float beam = p.has("beam_width") ? float(p.number_in("beam_width", 0.0, 0.0, 180.0)) : 0.75f * cutoff;
  if (beam > cutoff) p.fail("beam_width", "beam_width must not exceed cutoff_angle");
  const Vec3 up = p.has("up") ? read_direction(p, "up") : Vec3(0, 1, 0);
  const ColorParam texture = p.texture("texture", Color(1.0f));
  if (!texture.texture && texture.value != Color(1.0f)) p.fail("texture", "a spot's texture must be a texture (its colour goes in intensity)");
  if (texture.texture && !(cutoff < 89.0f)) p.fail("cutoff_angle", "a textured spot's cutoff_angle must be below 89 degrees (the texture is projected onto a plane)");
  return std::make_unique<PointLight>(pos, read_nonzero(p, "intensity"),
                                      std::make_shared<SpotProfile>(dir, cutoff, beam, up, texture.texture));
}

}  // namespace caustica
