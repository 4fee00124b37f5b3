// The shared part of the BSDF interface.
#include "core/bsdf/bsdf.h"
#include <algorithm>

namespace caustica {

bool SpecularBsdf::sample(const Vec3& wo, const Vec2&, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  BsdfSample lobes[2];
  const int n = specular_lobes(wo, lobes, sp);
  if (n == 0) return false;
  if (n == 1) {
    s = lobes[0];
    return true;
  }
  // Choose by the lobes' weights; the sample keeps weight / probability. For grey weights
  // (glass: F and 1 - F) that is exactly their sum, 1 for a lossless boundary.
  auto grey = [](const Color& c) { return c.x == c.y && c.y == c.z; };
  const float w0 = grey(lobes[0].weight) ? lobes[0].weight.x : average(lobes[0].weight);
  const float w1 = grey(lobes[1].weight) ? lobes[1].weight.x : average(lobes[1].weight);
  if (!(w0 + w1 > 0.0f)) return false;
  const bool first = u_lobe * (w0 + w1) < w0;
  s = first ? lobes[0] : lobes[1];
  s.weight = grey(s.weight) ? Color(w0 + w1) : s.weight * ((w0 + w1) / (first ? w0 : w1));
  return true;
}

float narrowest_glossy(const Bsdf& a, const Bsdf& b) {
  if (!a.has(kBsdfGlossy)) return b.glossy_roughness();
  if (!b.has(kBsdfGlossy)) return a.glossy_roughness();
  return std::min(a.glossy_roughness(), b.glossy_roughness());
}

bool complete_sample(const Bsdf& m, const Vec3& wo, const Vec3& wi, uint32_t lobe, bool below,
                     const ShadingPoint& sp, BsdfSample& s) {
  if (wi.z <= 0.0f) return false;
  s.pdf = m.pdf(wo, wi, sp);
  if (!(s.pdf > 0.0f)) return false;
  s.weight = m.eval(wo, wi, sp) * (wi.z / s.pdf);
  s.wi = below ? Vec3(wi.x, wi.y, -wi.z) : wi;
  s.delta = false;
  s.lobe = lobe;
  return true;
}

}  // namespace caustica
