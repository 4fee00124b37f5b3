// Two-sided wrapper.
#include "core/bsdf/twosided.h"
#include "core/bsdf/diffuse.h"

namespace caustica {

Color TwoSided::eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  return wo.z >= 0.0f ? front_->eval(wo, wi, sp) : back_->eval(flip_z(wo), flip_z(wi), sp);
}

float TwoSided::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  return wo.z >= 0.0f ? front_->pdf(wo, wi, sp) : back_->pdf(flip_z(wo), flip_z(wi), sp);
}

bool TwoSided::sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  if (wo.z >= 0.0f) return front_->sample(wo, u, u_lobe, s, sp);
  if (!back_->sample(flip_z(wo), u, u_lobe, s, sp)) return false;
  s.wi = flip_z(s.wi);
  return true;
}

int TwoSided::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  if (wo.z >= 0.0f) return front_->specular_lobes(wo, out, sp);
  const int n = back_->specular_lobes(flip_z(wo), out, sp);
  for (int i = 0; i < n; ++i) out[i].wi = flip_z(out[i].wi);
  return n;
}

Color TwoSided::null_transmission(const Vec3& wo, const ShadingPoint& sp) const {
  return wo.z >= 0.0f ? front_->null_transmission(wo, sp) : back_->null_transmission(flip_z(wo), sp);
}

float TwoSided::refraction_eta(const Vec3& wo, const ShadingPoint& sp) const {
  return wo.z >= 0.0f ? front_->refraction_eta(wo, sp) : back_->refraction_eta(flip_z(wo), sp);
}

std::unique_ptr<Bsdf> TwoSided::create(const Params& p) {
  const std::vector<const Bsdf*> sides = p.bsdfs("bsdf", true);
  return std::make_unique<TwoSided>(sides.front(), sides.back());
}

}  // namespace caustica
