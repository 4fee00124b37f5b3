#include "core/media/phase.h"
#include <algorithm>
#include <cmath>
#include "core/sampling.h"

namespace caustica {

float henyey_greenstein(float cos_theta, float g) {
  const float denom = 1.0f + g * g - 2.0f * g * cos_theta;
  return 0.25f * kInvPi * (1.0f - g * g) / (denom * std::sqrt(std::max(denom, 1e-12f)));
}

float IsotropicPhase::sample(const Vec3&, const Vec2& u, Vec3& wi) const {
  wi = sample_uniform_sphere(u);
  return 0.25f * kInvPi;
}

std::unique_ptr<PhaseFunction> IsotropicPhase::create(const Params&) { return std::make_unique<IsotropicPhase>(); }

float HenyeyGreenstein::eval(const Vec3& wo, const Vec3& wi) const { return henyey_greenstein(glm::dot(-wo, wi), g_); }

float HenyeyGreenstein::sample(const Vec3& wo, const Vec2& u, Vec3& wi) const {
  // The inverse of HG's cumulative distribution in cos theta (about the direction of travel).
  float cos_theta;
  if (std::abs(g_) < 1e-3f) {
    cos_theta = 1.0f - 2.0f * u.x;
  } else {
    const float s = (1.0f - g_ * g_) / (1.0f - g_ + 2.0f * g_ * u.x);
    cos_theta = (1.0f + g_ * g_ - s * s) / (2.0f * g_);
  }
  cos_theta = std::clamp(cos_theta, -1.0f, 1.0f);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = 2.0f * kPi * u.y;
  const Frame f(-wo);
  wi = f.to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
  return henyey_greenstein(cos_theta, g_);
}

std::unique_ptr<PhaseFunction> HenyeyGreenstein::create(const Params& p) {
  const double g = p.number("g", 0.8);
  if (!(g > -1.0 && g < 1.0)) p.fail("g", "g must lie in (-1, 1) (1 and -1 would scatter along one direction only)");
  return std::make_unique<HenyeyGreenstein>(float(g));
}

}  // namespace caustica
