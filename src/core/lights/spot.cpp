// Spot lights.
#include "core/lights/spot.h"
#include "core/lights/point.h"
#include "core/lights/read.h"

namespace caustica {

SpotProfile::SpotProfile(const Vec3& direction, float cutoff_deg, float beam_deg) : frame_(glm::normalize(direction)) {
  cutoff_ = cutoff_deg * kPi / 180.0f;
  beam_ = std::min(beam_deg, cutoff_deg) * kPi / 180.0f;
  cos_cutoff_ = std::cos(cutoff_);
  cos_beam_ = std::cos(beam_);
  // 2 pi [(1 - cos beam) + integral over the transition of falloff(theta) sin theta], the
  // transition by the midpoint rule.
  double sum = 1.0 - double(cos_beam_);
  const int steps = 4096;
  const double h = double(cutoff_ - beam_) / steps;
  for (int i = 0; i < steps && h > 0; ++i) {
    const double theta = double(beam_) + (i + 0.5) * h;
    sum += (double(cutoff_) - theta) / double(cutoff_ - beam_) * std::sin(theta) * h;
  }
  solid_angle_ = float(2.0 * 3.14159265358979323846 * sum);
}

float SpotProfile::falloff(const Vec3& dir) const {
  const float cos_t = glm::dot(dir, frame_.n);
  if (cos_t <= cos_cutoff_) return 0.0f;
  if (cos_t >= cos_beam_ || cutoff_ <= beam_) return 1.0f;
  return (cutoff_ - std::acos(std::min(1.0f, cos_t))) / (cutoff_ - beam_);
}

std::unique_ptr<Light> create_spot_light(const Params& p) {
  const Vec3 pos = p.point("position");
  Vec3 dir;
  if (p.has("target") == p.has("direction")) p.fail("", "give either direction or target");
  if (p.has("target")) {
    dir = p.point("target") - pos;
    if (!(glm::length(dir) > 0.0f)) p.fail("target", "target equals position");
  } else {
    dir = read_direction(p, "direction");
  }
  const float cutoff = float(p.number_in("cutoff_angle", 20.0, 0.01, 180.0));
  const float beam = p.has("beam_width") ? float(p.number_in("beam_width", 0.0, 0.0, 180.0)) : 0.75f * cutoff;
  if (beam > cutoff) p.fail("beam_width", "beam_width must not exceed cutoff_angle");
  return std::make_unique<PointLight>(pos, read_nonzero(p, "intensity"), SpotProfile(dir, cutoff, beam));
}

}  // namespace caustica
