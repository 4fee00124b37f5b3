// GGX (Trowbridge-Reitz; Walter et al. 2007) and Beckmann microfacet distributions.
#include "core/bsdf/microfacet.h"
#include "core/bsdf/bsdf.h"
#include "core/bsdf/fresnel.h"

namespace caustica {
namespace {
constexpr double kSqrtPi = 1.7724538509055160273;

// Inverse error function: a starting guess (Giles 2010's single-precision branch) refined by
// two Newton steps on std::erf in double precision.
double erf_inv(double y) {
  y = std::clamp(y, -1.0 + 1e-12, 1.0 - 1e-12);
  double w = -std::log((1.0 - y) * (1.0 + y)), x;
  if (w < 5.0) {
    w -= 2.5;
    double p = 2.81022636e-08;
    for (double c : {3.43273939e-07, -3.5233877e-06, -4.39150654e-06, 0.00021858087, -0.00125372503,
                     -0.00417768164, 0.246640727, 1.50140941}) p = c + p * w;
    x = p * y;
  } else {
    w = std::sqrt(w) - 3.0;
    double p = -0.000200214257;
    for (double c : {0.000100950558, 0.00134934322, -0.00367342844, 0.00573950773, -0.0076224613,
                     0.00943887047, 1.00167406, 2.83297682}) p = c + p * w;
    x = p * y;
  }
  for (int i = 0; i < 2; ++i) x -= (std::erf(x) - y) / (2.0 / kSqrtPi * std::exp(-x * x));
  return x;
}
}  // namespace

MicrofacetDistribution::MicrofacetDistribution(MicrofacetType type, float alpha_u, float alpha_v)
    : type_(type), ax_(clamp_alpha(alpha_u)), ay_(clamp_alpha(alpha_v)) {}

float MicrofacetDistribution::D(const Vec3& m) const {
  if (m.z <= 0.0f) return 0.0f;
  const float cos2 = m.z * m.z;
  // tan^2(theta) (cos^2 phi / ax^2 + sin^2 phi / ay^2), written in the components of m.
  const float e = ((m.x * m.x) / (ax_ * ax_) + (m.y * m.y) / (ay_ * ay_)) / cos2;
  if (type_ == MicrofacetType::Beckmann) return std::exp(-e) / (kPi * ax_ * ay_ * cos2 * cos2);
  const float d = 1.0f + e;
  return 1.0f / (kPi * ax_ * ay_ * cos2 * cos2 * d * d);
}

float MicrofacetDistribution::lambda(const Vec3& w) const {
  // alpha_o tan(theta): the roughness along w's azimuth times its tangent.
  const float at2 = (ax_ * ax_ * w.x * w.x + ay_ * ay_ * w.y * w.y) / (w.z * w.z);
  if (!(at2 > 0.0f)) return 0.0f;
  if (!std::isfinite(at2)) return kInfinity;
  if (type_ == MicrofacetType::GGX) return 0.5f * (std::sqrt(1.0f + at2) - 1.0f);
  const double a = 1.0 / std::sqrt(double(at2));
  return float(0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * kSqrtPi));
}

float MicrofacetDistribution::pdf(const Vec3& wo, const Vec3& m) const {
  // Only normals facing wo (or -wo from below) are visible: sample_visible returns no others.
  const float wom = glm::dot(wo, m);
  if (wo.z == 0.0f || wom * wo.z <= 0.0f) return 0.0f;
  return G1(wo) * std::abs(wom) * D(m) / std::abs(wo.z);
}

Vec2 MicrofacetDistribution::sample_beckmann_slopes(float cos_theta, const Vec2& u) const {
  // Slopes of the visible normals of the unit-roughness Beckmann distribution for a direction
  // at theta in the xz-plane. Visible projected area per slope: (1 - x tan) exp(-x^2) / sqrt(pi)
  // for x < cot, so CDF(x) = [1 + erf(x) + tan exp(-x^2) / sqrt(pi)] / Z; y is independent.
  const double y = erf_inv(2.0 * std::clamp(double(u.y), 1e-7, 1.0 - 1e-7) - 1.0);
  const double c = std::clamp(double(cos_theta), 1e-6, 1.0);
  if (c > 0.99999) return Vec2(float(erf_inv(2.0 * std::clamp(double(u.x), 1e-7, 1.0 - 1e-7) - 1.0)), float(y));
  const double tan_t = std::sqrt(1.0 - c * c) / c, cot_t = 1.0 / tan_t;
  auto cdf = [&](double x) { return 1.0 + std::erf(x) + tan_t / kSqrtPi * std::exp(-x * x); };
  const double z = cdf(cot_t);
  const double target = std::clamp(double(u.x), 1e-7, 1.0 - 1e-7) * z;
  double lo = -8.0, hi = cot_t, x = std::min(0.0, cot_t);
  for (int i = 0; i < 60; ++i) {
    const double f = cdf(x) - target;
    if (std::abs(f) < 1e-9 * z) break;
    if (f > 0) hi = x; else lo = x;
    const double dfdx = 2.0 / kSqrtPi * std::exp(-x * x) * (1.0 - x * tan_t);
    double next = dfdx > 0 ? x - f / dfdx : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // keep Newton inside the bracket
    x = next;
  }
  return Vec2(float(x), float(y));
}

Vec3 MicrofacetDistribution::sample_visible(const Vec3& wo_in, const Vec2& u) const {
  // Seen from below (inside a dielectric), the normals visible from -wo: the same upper set.
  const Vec3 wo = wo_in.z < 0.0f ? -wo_in : wo_in;
  // Stretch the view direction to the unit-roughness configuration.
  const Vec3 vh = glm::normalize(Vec3(ax_ * wo.x, ay_ * wo.y, wo.z));
  if (type_ == MicrofacetType::GGX) {
    // Heitz 2018, "Sampling the GGX distribution of visible normals": a point on the projected
    // hemisphere of the stretched view, then unstretched.
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = len2 > 0.0f ? Vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : Vec3(1.0f, 0.0f, 0.0f);
    const Vec3 t2 = glm::cross(vh, t1);
    const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1.0f + vh.z);
    const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
    const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(Vec3(ax_ * nh.x, ay_ * nh.y, std::max(1e-6f, nh.z)));
  }
  // Beckmann: slopes for the stretched direction, rotated to its azimuth, then unstretched.
  const Vec2 s = sample_beckmann_slopes(vh.z, u);
  const float sin_t = std::sqrt(std::max(0.0f, 1.0f - vh.z * vh.z));
  const float cos_p = sin_t > 0 ? vh.x / sin_t : 1.0f, sin_p = sin_t > 0 ? vh.y / sin_t : 0.0f;
  const float sx = (cos_p * s.x - sin_p * s.y) * ax_;
  const float sy = (sin_p * s.x + cos_p * s.y) * ay_;
  return glm::normalize(Vec3(-sx, -sy, 1.0f));
}

// A rough boundary's directional reflectance and transmittance (fractions of energy, single
// scattering: their sum falls below 1 as the surface gets rougher) for light arriving at cos
// theta from the side where the relative index is eta; stratified visible normals, m x m. From
// inside (eta < 1), where total internal reflection makes the rare steep microfacets matter,
// 96 x 96: with 32 x 32, GGX's R at normal incidence was 20 % high.
std::pair<double, double> rough_boundary(const MicrofacetDistribution& dist, float cos_theta, float eta) {
  const int m = eta < 1.0f ? 96 : 32;
  const float c = std::max(1e-3f, cos_theta);
  const Vec3 wo(std::sqrt(1.0f - c * c), 0.0f, c);
  double r = 0, t = 0;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      const Vec3 h = dist.sample_visible(wo, Vec2((i + 0.5f) / m, (j + 0.5f) / m));
      const float woh = glm::dot(wo, h);
      if (woh <= 0.0f) continue;
      const float f = fresnel_dielectric(woh, eta);
      const Vec3 wr = reflect(wo, h);
      // Visible normals from wo; the way out is masked by Smith's G1, as Mitsuba's
      // eval_reflectance and eval_transmittance weigh it.
      if (wr.z > 0.0f) r += double(f) * double(dist.G1(wr));
      Vec3 wt;
      if (f < 1.0f && refract(wo, h, eta, wt) && wt.z < 0.0f) t += double(1.0f - f) * double(dist.G1(wt));
    }
  }
  return {r / (m * m), t / (m * m)};
}

float reflection_pdf(const MicrofacetDistribution& dist, const Vec3& wo_in, const Vec3& wi_in) {
  if (wo_in.z * wi_in.z <= 0.0f) return 0.0f;
  // Mirrored up in z, as the BSDFs' two-sided lobes are.
  const bool below = wo_in.z < 0;
  const Vec3 wo = below ? Vec3(wo_in.x, wo_in.y, -wo_in.z) : wo_in, wi = below ? Vec3(wi_in.x, wi_in.y, -wi_in.z) : wi_in;
  const Vec3 h = glm::normalize(wo + wi);
  const float woh = glm::dot(wo, h);
  return woh > 0.0f ? dist.pdf(wo, h) / (4.0f * woh) : 0.0f;
}

Roughness::Roughness(MicrofacetType type, const ColorParam& alpha_u, const ColorParam& alpha_v)
    : fixed_(type, clamp_alpha(alpha_u.value.x), clamp_alpha(alpha_v.value.x)),
      alpha_u_(alpha_u),
      alpha_v_(alpha_v),
      textured_(alpha_u.texture || alpha_v.texture) {}

MicrofacetDistribution Roughness::at(const TexturePoint& uv) const {
  if (!textured_) return fixed_;
  auto alpha = [&](const ColorParam& a) {
    return clamp_alpha(a.texture ? luminance(a.texture->eval(uv)) : a.value.x);
  };
  return MicrofacetDistribution(fixed_.type(), alpha(alpha_u_), alpha(alpha_v_));
}

}  // namespace caustica
