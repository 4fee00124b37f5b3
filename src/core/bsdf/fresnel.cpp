// Fresnel equations (Born & Wolf, ch. 1.5 and 14.2).
#include "core/bsdf/fresnel.h"
#include <complex>

namespace caustica {

float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  const float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

float fresnel_schlick(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  // Schlick's approximation uses the angle on the optically thinner side.
  const float cos_x = eta >= 1.0f ? cos_i : std::sqrt(1.0f - sin2_t);
  const float r0 = ((eta - 1.0f) / (eta + 1.0f)) * ((eta - 1.0f) / (eta + 1.0f));
  const float m = 1.0f - cos_x;
  return r0 + (1.0f - r0) * m * m * m * m * m;
}

Color fresnel_conductor(float cos_i, const Color& eta, const Color& k) {
  using C = std::complex<double>;
  const double c = std::clamp(double(cos_i), 0.0, 1.0);
  const double sin2 = 1.0 - c * c;
  Color r;
  for (int ch = 0; ch < 3; ++ch) {
    const C n(eta[ch], k[ch]);
    if (n == C(0.0)) {  // the limit of a vanishing index (a named table's clamped channel): a mirror
      r[ch] = 1.0f;
      continue;
    }
    const C cos_t = std::sqrt(1.0 - sin2 / (n * n));  // Snell's law with a complex index
    const C rs = (c - n * cos_t) / (c + n * cos_t);
    const C rp = (n * c - cos_t) / (n * c + cos_t);
    r[ch] = float(0.5 * (std::norm(rs) + std::norm(rp)));
  }
  return r;
}

bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3& wt) {
  const float cos_i = glm::dot(wi, n);
  const float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  wt = -wi / eta + (cos_i / eta - cos_t) * n;
  return true;
}

}  // namespace caustica
