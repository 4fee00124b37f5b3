// Smooth and rough conductors. The rough one is Cook-Torrance with Smith's height-correlated
// masking-shadowing and sampling of the visible normals (Heitz 2014, 2018).
#include "core/bsdf/conductor.h"
#include "core/bsdf/bsdf_params.h"
#include "core/bsdf/diffuse.h"
#include "core/bsdf/fresnel.h"

namespace caustica {

Color ConductorIor::reflectance(float cos_i) const {
  return perfect() ? Color(1.0f) : fresnel_conductor(cos_i, eta, k);
}

int Conductor::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  if (wo.z == 0.0f) return 0;
  out->wi = reflect_local(wo);
  out->weight = specular_.at(sp) * ior_.reflectance(std::abs(wo.z));
  out->pdf = 0.0f;
  out->delta = true;
  out->lobe = kBsdfSpecular | kBsdfReflection;
  return 1;
}

int RoughConductor::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  return smooth().specular_lobes(wo, out, sp);
}

Color RoughConductor::eval(const Vec3& wo_in, const Vec3& wi_in, const ShadingPoint& sp) const {
  if (wo_in.z * wi_in.z <= 0.0f) return Color(0.0f);
  const Vec3 wo = wo_in.z < 0 ? flip_z(wo_in) : wo_in, wi = wo_in.z < 0 ? flip_z(wi_in) : wi_in;
  const Vec3 h = glm::normalize(wo + wi);
  const MicrofacetDistribution dist = rough_.at(sp);
  const float d = dist.D(h);
  if (d <= 0.0f) return Color(0.0f);
  return specular_.at(sp) * ior_.reflectance(glm::dot(wo, h)) * (d * dist.G(wo, wi) / (4.0f * wo.z * wi.z));
}

float RoughConductor::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  return reflection_pdf(rough_.at(sp), wo, wi);
}

bool RoughConductor::sample(const Vec3& wo_in, const Vec2& u, float, BsdfSample& s, const ShadingPoint& sp) const {
  if (wo_in.z == 0.0f) return false;
  const bool below = wo_in.z < 0;
  const Vec3 wo = below ? flip_z(wo_in) : wo_in;
  const MicrofacetDistribution dist = rough_.at(sp);
  const Vec3 m = dist.sample_visible(wo, u);
  const float wom = glm::dot(wo, m);
  if (wom <= 0.0f) return false;
  const Vec3 wi = reflect(wo, m);
  if (wi.z <= 0.0f) return false;
  s.pdf = dist.pdf(wo, m) / (4.0f * wom);
  if (!(s.pdf > 0.0f)) return false;
  // f cos / pdf = F D G / (4 cos_o) / (G1(wo) D / (4 cos_o)) = F G / G1(wo).
  s.weight = specular_.at(sp) * ior_.reflectance(wom) * (dist.G(wo, wi) / dist.G1(wo));
  s.wi = below ? flip_z(wi) : wi;
  s.delta = false;
  s.lobe = kBsdfGlossy | kBsdfReflection;
  return true;
}

std::unique_ptr<Bsdf> Conductor::create(const Params& p) {
  return std::make_unique<Conductor>(read_conductor(p), p.texture("specular_reflectance", Color(1.0f)));
}

std::unique_ptr<Bsdf> Conductor::create_mirror(const Params& p) {
  return std::make_unique<Conductor>(ConductorIor{}, p.texture("reflectance", Color(1.0f)));
}

std::unique_ptr<Bsdf> RoughConductor::create(const Params& p) {
  return std::make_unique<RoughConductor>(read_roughness(p), read_conductor(p), p.texture("specular_reflectance", Color(1.0f)));
}

}  // namespace caustica
