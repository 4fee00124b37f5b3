// Blend of two BSDFs.
#include "core/bsdf/blend.h"
#include <algorithm>

namespace caustica {

float BlendBsdf::weight(const ShadingPoint& sp) const {
  return std::clamp(weight_.texture ? luminance(weight_.texture->eval(sp)) : weight_.value.x, 0.0f, 1.0f);
}

Color BlendBsdf::eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  const float w = weight(sp);
  return (1.0f - w) * a_->eval(wo, wi, sp) + w * b_->eval(wo, wi, sp);
}

float BlendBsdf::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  const float w = weight(sp);
  return (1.0f - w) * a_->pdf(wo, wi, sp) + w * b_->pdf(wo, wi, sp);
}

bool BlendBsdf::sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  const float w = weight(sp);
  // The component by the weight; u_lobe, rescaled, chooses within it.
  const bool second = u_lobe < w;
  const float u_inner = second ? u_lobe / w : (u_lobe - w) / (1.0f - w);
  const Bsdf& chosen = second ? *b_ : *a_;
  if (!chosen.sample(wo, u, std::min(u_inner, 0x1.fffffep-1f), s, sp)) return false;
  // A delta lobe: its weight times the component's weight over the probability of choosing it.
  if (s.delta) return true;
  // Otherwise the mixture's density and value in that direction (the other component's delta
  // lobes have none).
  s.pdf = pdf(wo, s.wi, sp);
  if (!(s.pdf > 0.0f)) return false;
  s.weight = eval(wo, s.wi, sp) * (std::abs(s.wi.z) / s.pdf);
  return true;
}

int BlendBsdf::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  const float w = weight(sp);
  BsdfSample la[2], lb[2];
  const int na = a_->has(kBsdfSpecular) && w < 1.0f ? a_->specular_lobes(wo, la, sp) : 0;
  const int nb = b_->has(kBsdfSpecular) && w > 0.0f ? b_->specular_lobes(wo, lb, sp) : 0;
  BsdfSample all[4];
  int n = 0;
  auto add = [&](BsdfSample l, float scale) {
    l.weight *= scale;
    for (int i = 0; i < n; ++i) {
      if (glm::dot(all[i].wi, l.wi) > 1.0f - 1e-6f) {  // the same direction: one lobe
        all[i].weight += l.weight;
        all[i].lobe |= l.lobe;
        return;
      }
    }
    all[n++] = l;
  };
  for (int i = 0; i < na; ++i) add(la[i], 1.0f - w);
  for (int i = 0; i < nb; ++i) add(lb[i], w);
  if (n > 2) return 0;
  for (int i = 0; i < n; ++i) out[i] = all[i];
  return n;
}

Color BlendBsdf::albedo(const ShadingPoint& sp) const {
  const float w = weight(sp);
  return (1.0f - w) * a_->albedo(sp) + w * b_->albedo(sp);
}

std::unique_ptr<Bsdf> BlendBsdf::create(const Params& p) {
  const ColorParam weight = p.texture("weight", Color(0.5f));
  if (!weight.texture) {
    const Color& c = weight.value;
    if (!(c.x >= 0.0f && c.x <= 1.0f) || c.y != c.x || c.z != c.x) p.fail("weight", "weight must be one number in [0, 1]");
  }
  const std::vector<const Bsdf*> parts = p.bsdfs("bsdf", true);
  if (parts.size() != 2) p.fail("bsdf", "blendbsdf takes two BSDFs: [first, second]");
  return std::make_unique<BlendBsdf>(parts[0], parts[1], weight);
}

}  // namespace caustica
