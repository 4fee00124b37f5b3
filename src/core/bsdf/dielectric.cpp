// Smooth, thin and rough dielectrics.
#include "core/bsdf/dielectric.h"
#include "core/bsdf/bsdf_params.h"

namespace caustica {
namespace {
BsdfSample delta_sample(const Vec3& wi, float weight, uint32_t lobe) {
  BsdfSample s;
  s.wi = wi;
  s.weight = Color(weight);
  s.pdf = 0.0f;
  s.delta = true;
  s.lobe = kBsdfSpecular | lobe;
  return s;
}
}  // namespace

float Dielectric::reflectance(const Vec3& wo) const {
  const float eta = wo.z > 0.0f ? eta_ : 1.0f / eta_;
  const float cos_i = std::abs(wo.z);
  return model_ == FresnelModel::Exact ? fresnel_dielectric(cos_i, eta) : fresnel_schlick(cos_i, eta);
}

bool Dielectric::refract(const Vec3& wo, Vec3& wt) const {
  const Vec3 n(0.0f, 0.0f, wo.z > 0.0f ? 1.0f : -1.0f);
  return caustica::refract(wo, n, wo.z > 0.0f ? eta_ : 1.0f / eta_, wt);
}

int Dielectric::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  if (wo.z == 0.0f) return 0;
  Vec3 wt;
  if (!refract(wo, wt)) {
    out[0] = delta_sample(reflect_local(wo), 1.0f, kBsdfReflection);
    out[0].weight *= tint_.reflect.at(sp);
    return 1;
  }
  const float f = reflectance(wo);
  out[0] = delta_sample(reflect_local(wo), f, kBsdfReflection);
  out[1] = delta_sample(wt, 1.0f - f, kBsdfTransmission);
  out[0].weight *= tint_.reflect.at(sp);
  out[1].weight *= tint_.transmit.at(sp);
  return 2;
}

float ThinDielectric::reflectance(float cos_i) const {
  const float r = fresnel_dielectric(cos_i, eta_);
  return r < 1.0f ? 2.0f * r / (1.0f + r) : 1.0f;
}

int ThinDielectric::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  if (wo.z == 0.0f) return 0;
  const float r = reflectance(std::abs(wo.z));
  out[0] = delta_sample(reflect_local(wo), r, kBsdfReflection);
  out[1] = delta_sample(-wo, 1.0f - r, kBsdfTransmission | kBsdfNull);
  out[0].weight *= tint_.reflect.at(sp);
  out[1].weight *= tint_.transmit.at(sp);
  return 2;
}

Color ThinDielectric::null_transmission(const Vec3& wo, const ShadingPoint& sp) const {
  return (1.0f - reflectance(std::abs(wo.z))) * tint_.transmit.at(sp);
}

bool RoughDielectric::half_vector(const Vec3& wo, const Vec3& wi, Vec3& wm, float& etap) const {
  if (wo.z == 0.0f || wi.z == 0.0f) return false;
  const bool reflection = wo.z * wi.z > 0.0f;
  etap = reflection ? 1.0f : (wo.z > 0.0f ? eta_ : 1.0f / eta_);
  wm = wi * etap + wo;  // generalised half vector (Walter et al. eq. 16)
  const float len2 = glm::dot(wm, wm);
  if (!(len2 > 0.0f)) return false;
  wm /= std::sqrt(len2);
  if (wm.z < 0.0f) wm = -wm;
  // Both directions must lie on the same side of the microfacet as of the macro surface.
  return glm::dot(wm, wi) * wi.z > 0.0f && glm::dot(wm, wo) * wo.z > 0.0f;
}

Color RoughDielectric::eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  Vec3 wm;
  float etap;
  if (!half_vector(wo, wi, wm, etap)) return Color(0.0f);
  const float F = fresnel_dielectric(std::abs(glm::dot(wo, wm)), wo.z > 0.0f ? eta_ : 1.0f / eta_);
  const MicrofacetDistribution dist = rough_.at(sp);
  const float dg = dist.D(wm) * dist.G(wo, wi);
  if (wo.z * wi.z > 0.0f) return Color(F * dg / std::abs(4.0f * wo.z * wi.z)) * tint_.reflect.at(sp);
  const float denom = glm::dot(wi, wm) + glm::dot(wo, wm) / etap;
  const float ft = (1.0f - F) * dg * std::abs(glm::dot(wi, wm) * glm::dot(wo, wm) / (denom * denom * wi.z * wo.z));
  return Color(ft) * tint_.transmit.at(sp);
}

float RoughDielectric::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  Vec3 wm;
  float etap;
  if (!half_vector(wo, wi, wm, etap)) return 0.0f;
  const float F = fresnel_dielectric(std::abs(glm::dot(wo, wm)), wo.z > 0.0f ? eta_ : 1.0f / eta_);
  const float pm = rough_.at(sp).pdf(wo, wm);
  if (wo.z * wi.z > 0.0f) return pm / (4.0f * std::abs(glm::dot(wo, wm))) * F;
  const float denom = glm::dot(wi, wm) + glm::dot(wo, wm) / etap;
  return pm * std::abs(glm::dot(wi, wm)) / (denom * denom) * (1.0f - F);
}

bool RoughDielectric::sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  if (wo.z == 0.0f) return false;
  const Vec3 wm = rough_.at(sp).sample_visible(wo, u);
  const float cos_om = glm::dot(wo, wm);
  const float F = fresnel_dielectric(std::abs(cos_om), wo.z > 0.0f ? eta_ : 1.0f / eta_);
  if (u_lobe < F) {
    s.wi = reflect(wo, wm);
    if (s.wi.z * wo.z <= 0.0f) return false;
    s.lobe = kBsdfGlossy | kBsdfReflection;
  } else {
    // Refract through the microfacet, facing it towards wo's side.
    const Vec3 n = cos_om > 0.0f ? wm : -wm;
    if (!refract(wo, n, wo.z > 0.0f ? eta_ : 1.0f / eta_, s.wi) || s.wi.z * wo.z >= 0.0f) return false;
    s.lobe = kBsdfGlossy | kBsdfTransmission;
  }
  s.pdf = pdf(wo, s.wi, sp);
  if (!(s.pdf > 0.0f)) return false;
  s.weight = eval(wo, s.wi, sp) * (std::abs(s.wi.z) / s.pdf);
  s.delta = false;
  return true;
}

std::unique_ptr<Bsdf> Dielectric::create(const Params& p) {
  const float eta = read_eta(p, 1.5046f);
  return std::make_unique<Dielectric>(eta, FresnelModel::Exact, read_dielectric_tint(p));
}

std::unique_ptr<Bsdf> Dielectric::create_glass(const Params& p) {
  const float ior = read_ior(p, "ior", 1.5f);
  FresnelModel model = FresnelModel::Exact;
  if (p.has("fresnel")) {
    const std::string f = p.string("fresnel", "exact");
    if (f == "schlick") model = FresnelModel::Schlick;
    else if (f != "exact") p.fail("fresnel", "unknown Fresnel model \"" + f + "\" (known: exact, schlick)");
  }
  return std::make_unique<Dielectric>(ior, model);
}

std::unique_ptr<Bsdf> ThinDielectric::create(const Params& p) {
  const float eta = read_eta(p, 1.5046f);
  return std::make_unique<ThinDielectric>(eta, read_dielectric_tint(p));
}

std::unique_ptr<Bsdf> RoughDielectric::create(const Params& p) {
  const Roughness rough = read_roughness(p);
  const float eta = read_eta(p, 1.5046f);
  return std::make_unique<RoughDielectric>(rough, eta, read_dielectric_tint(p));
}

}  // namespace caustica
