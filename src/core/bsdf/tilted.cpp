// Nested BSDFs in a tilted shading frame.
#include "core/bsdf/tilted.h"

namespace caustica {

Color TiltedFrameBsdf::eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  const Frame& f = frame_at(sp);
  const Vec3 wi_p = f.to_local(wi);
  if (!(wi.z * wi_p.z > 0.0f)) return Color(0.0f);
  const float scale = std::abs(wi_p.z) / std::abs(wi.z);  // 1 exactly for an untilted frame
  return nested_->eval(f.to_local(wo), wi_p, sp) * scale;
}

float TiltedFrameBsdf::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  const Frame& f = frame_at(sp);
  const Vec3 wi_p = f.to_local(wi);
  if (!(wi.z * wi_p.z > 0.0f)) return 0.0f;
  return nested_->pdf(f.to_local(wo), wi_p, sp);
}

bool TiltedFrameBsdf::sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  const Frame& f = frame_at(sp);
  if (!nested_->sample(f.to_local(wo), u, u_lobe, s, sp)) return false;
  const Vec3 wi = f.to_world(s.wi);
  if (!(wi.z * s.wi.z > 0.0f)) return false;
  s.wi = wi;  // weight and density carry over: the frames differ by a rotation
  return true;
}

int TiltedFrameBsdf::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  const Frame& f = frame_at(sp);
  BsdfSample lobes[2];
  const int n = nested_->specular_lobes(f.to_local(wo), lobes, sp);
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 wi = f.to_world(lobes[i].wi);
    if (!(wi.z * lobes[i].wi.z > 0.0f)) continue;
    out[kept] = lobes[i];
    out[kept++].wi = wi;
  }
  return kept;
}

}  // namespace caustica
