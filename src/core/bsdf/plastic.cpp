// Smooth and rough plastic.
#include "core/bsdf/plastic.h"
#include "core/bsdf/bsdf_params.h"
#include "core/bsdf/diffuse.h"
#include "core/bsdf/fresnel.h"
#include "core/sampling.h"
#include <tbb/parallel_for.h>
#include <vector>

namespace caustica {
namespace {
// Diffuse reflectance of a boundary for light from the side where the relative index is eta:
// the cosine-weighted hemispherical average of Fresnel, 2 int F(cos) cos d(cos).
float diffuse_fresnel(float eta) {
  const int n = 2048;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double c = (i + 0.5) / n;
    sum += double(fresnel_dielectric(float(c), eta)) * 2.0 * c / n;
  }
  return float(sum);
}

}  // namespace

Plastic::Plastic(const ColorParam& diffuse, const ColorParam& specular, float eta, bool nonlinear,
                 std::optional<MicrofacetDistribution> dist)
    : diffuse_(diffuse), specular_(specular), eta_(eta), nonlinear_(nonlinear), dist_(dist) {
  if (!dist_) {
    // The smooth coat's diffuse reflectance from inside, and from outside: 2 integral of its
    // reflectance cos d(cos).
    fdr_internal_ = diffuse_fresnel(1.0f / eta_);
    const int n = 1024;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const double c = (i + 0.5) / n;
      sum += double(coat_reflectance(float(c))) * 2.0 * c / n;
    }
    fdr_external_ = float(sum);
    return;
  }
  // The rough coat from outside: its directional albedo E(cos) (the integral of
  // F D G / (4 cos_o) over wi) and transmittance T(cos), tabulated over cos (deterministic).
  rough_albedo_.v.resize(CosineTable::kSize + 1);
  rough_transmittance_.v.resize(CosineTable::kSize + 1);
  tbb::parallel_for(0, CosineTable::kSize + 1, [&](int k) {
    const auto [r, t] = rough_boundary(*dist_, float(k) / CosineTable::kSize, eta_);
    rough_albedo_.v[size_t(k)] = float(r);
    rough_transmittance_.v[size_t(k)] = float(t);
  });
  // And from inside, as Mitsuba's roughplastic: the rough coat's own diffuse internal
  // reflectance, 2 integral of its reflectance (total internal reflection included) cos.
  // Summed in order, so the result is the same for any thread count.
  constexpr int n = 48;
  std::vector<double> terms(n);
  tbb::parallel_for(0, n, [&](int i) {
    const double c = (i + 0.5) / n;
    terms[size_t(i)] = rough_boundary(*dist_, float(c), 1.0f / eta_).first * 2.0 * c / n;
  });
  double sum = 0;
  for (double x : terms) sum += x;
  fdr_internal_ = float(sum);
}

uint32_t Plastic::flags() const {
  uint32_t f = kBsdfReflection | (dist_ ? kBsdfGlossy : kBsdfSpecular);
  if (!diffuse_.is_black()) f |= kBsdfDiffuse;
  return f;
}


float Plastic::coat_reflectance(float cos_theta) const {
  if (!dist_) return fresnel_dielectric(std::clamp(cos_theta, 0.0f, 1.0f), eta_);
  return rough_albedo_(cos_theta);
}

float Plastic::specular_probability(float cos_o, const ShadingPoint& sp) const {
  // The coat's share by its reflectance and tint against the transmitted diffuse part.
  const float s = coat_reflectance(cos_o) * average(specular_.at(sp));
  const float d = (1.0f - coat_reflectance(cos_o)) * average(diffuse_.at(sp));
  return s + d > 0.0f ? s / (s + d) : 0.0f;
}

Color Plastic::diffuse_eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  const Color rho = diffuse_.at(sp);
  if (dist_) {
    // Mitsuba's roughplastic: rho / (1 - F_dr_int) (nonlinear: 1 - rho F_dr_int) / (pi eta^2)
    // times the rough coat's transmittance on the way in and out, with the rough coat's own
    // F_dr_int. Not lossless: the single-scattering coat loses energy as it gets rougher.
    const Color denom = Color(1.0f) - (nonlinear_ ? rho * fdr_internal_ : Color(fdr_internal_));
    const float t = rough_transmittance_(wi.z) * rough_transmittance_(wo.z);
    return rho / denom * (t * kInvPi / (eta_ * eta_));
  }
  // rho / (pi (1 - F_dr_ext)) is Mitsuba's rho / (pi eta^2 (1 - F_dr_int)) for a smooth coat.
  const Color base = nonlinear_ ? rho * (1.0f - fdr_internal_) / (Color(1.0f) - rho * fdr_internal_) : rho;
  const float t = (1.0f - coat_reflectance(wi.z)) * (1.0f - coat_reflectance(wo.z));
  return base * (t * kInvPi / (1.0f - fdr_external_));
}

Color Plastic::coat_eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  if (!dist_) return Color(0.0f);
  const Vec3 h = glm::normalize(wo + wi);
  const float d = dist_->D(h);
  if (d <= 0.0f) return Color(0.0f);
  return specular_.at(sp) * (fresnel_dielectric(glm::dot(wo, h), eta_) * d * dist_->G(wo, wi) / (4.0f * wo.z * wi.z));
}

float Plastic::coat_pdf(const Vec3& wo, const Vec3& wi) const {
  if (!dist_) return 0.0f;
  const Vec3 h = glm::normalize(wo + wi);
  const float woh = glm::dot(wo, h);
  return woh > 0.0f ? dist_->pdf(wo, h) / (4.0f * woh) : 0.0f;
}

Color Plastic::eval(const Vec3& wo_in, const Vec3& wi_in, const ShadingPoint& sp) const {
  if (wo_in.z * wi_in.z <= 0.0f) return Color(0.0f);
  const Vec3 wo = wo_in.z < 0 ? flip_z(wo_in) : wo_in, wi = wo_in.z < 0 ? flip_z(wi_in) : wi_in;
  return diffuse_eval(wo, wi, sp) + coat_eval(wo, wi, sp);
}

float Plastic::pdf(const Vec3& wo_in, const Vec3& wi_in, const ShadingPoint& sp) const {
  if (wo_in.z * wi_in.z <= 0.0f) return 0.0f;
  const Vec3 wo = wo_in.z < 0 ? flip_z(wo_in) : wo_in, wi = wo_in.z < 0 ? flip_z(wi_in) : wi_in;
  const float p = specular_probability(wo.z, sp);
  return p * coat_pdf(wo, wi) + (1.0f - p) * wi.z * kInvPi;
}

bool Plastic::sample(const Vec3& wo_in, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  if (wo_in.z == 0.0f) return false;
  const bool below = wo_in.z < 0;
  const Vec3 wo = below ? flip_z(wo_in) : wo_in;
  const float p = specular_probability(wo.z, sp);
  if (u_lobe < p && !dist_) {
    // The smooth coat: a delta lobe chosen with probability p.
    s.wi = reflect_local(wo);
    s.weight = specular_.at(sp) * (coat_reflectance(wo.z) / p);
    s.pdf = 0.0f;
    s.delta = true;
    s.lobe = kBsdfSpecular | kBsdfReflection;
    if (below) s.wi = flip_z(s.wi);
    return true;
  }
  const bool glossy = u_lobe < p;
  const Vec3 wi = glossy ? reflect(wo, dist_->sample_visible(wo, u)) : sample_cosine_hemisphere(u);
  return complete_sample(*this, wo, wi, kBsdfReflection | (glossy ? kBsdfGlossy : kBsdfDiffuse), below, sp, s);
}

int Plastic::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  // The coat's mirror reflection (for a rough coat, its smooth limit).
  if (wo.z == 0.0f) return 0;
  out->wi = reflect_local(wo);
  out->weight = specular_.at(sp) * fresnel_dielectric(std::abs(wo.z), eta_);
  out->pdf = 0.0f;
  out->delta = true;
  out->lobe = kBsdfSpecular | kBsdfReflection;
  return 1;
}

Color Plastic::albedo(const ShadingPoint& sp) const {
  const float f = coat_reflectance(1.0f);
  return specular_.at(sp) * f + diffuse_.at(sp) * (1.0f - f);
}

namespace {
std::unique_ptr<Bsdf> create_plastic(const Params& p, bool rough) {
  const ColorParam kd = p.texture("diffuse_reflectance", Color(0.5f));
  check_albedo(p, "diffuse_reflectance", kd);
  const bool nonlinear = p.boolean("nonlinear", false);
  std::optional<MicrofacetDistribution> dist;
  if (rough) dist = read_distribution(p);
  return std::make_unique<Plastic>(kd, p.texture("specular_reflectance", Color(1.0f)), read_eta(p, 1.49f), nonlinear, dist);
}
}  // namespace

std::unique_ptr<Bsdf> Plastic::create(const Params& p) { return create_plastic(p, false); }
std::unique_ptr<Bsdf> Plastic::create_rough(const Params& p) { return create_plastic(p, true); }

}  // namespace caustica
