// Two-sided wrapper.
#include "core/bsdf/twosided.h"
#include "core/bsdf/diffuse.h"

namespace caustica {

Color TwoSided::eval(const Vec3& wo, const Vec3& wi) const {
  return wo.z >= 0.0f ? front_->eval(wo, wi) : back_->eval(flip_z(wo), flip_z(wi));
}

float TwoSided::pdf(const Vec3& wo, const Vec3& wi) const {
  return wo.z >= 0.0f ? front_->pdf(wo, wi) : back_->pdf(flip_z(wo), flip_z(wi));
}

bool TwoSided::sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s) const {
  if (wo.z >= 0.0f) return front_->sample(wo, u, u_lobe, s);
  if (!back_->sample(flip_z(wo), u, u_lobe, s)) return false;
  s.wi = flip_z(s.wi);
  return true;
}

int TwoSided::specular_lobes(const Vec3& wo, BsdfSample* out) const {
  if (wo.z >= 0.0f) return front_->specular_lobes(wo, out);
  const int n = back_->specular_lobes(flip_z(wo), out);
  for (int i = 0; i < n; ++i) out[i].wi = flip_z(out[i].wi);
  return n;
}

float TwoSided::glossy_roughness() const {
  const float a = front_->glossy_roughness(), b = back_->glossy_roughness();
  if (!front_->has(kBsdfGlossy)) return b;
  if (!back_->has(kBsdfGlossy)) return a;
  return std::min(a, b);
}

}  // namespace caustica
