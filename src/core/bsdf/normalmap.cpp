// Normal mapping.
#include "core/bsdf/normalmap.h"

namespace caustica {

Frame NormalMap::frame(const ShadingPoint& sp) const {
  const Vec3 n = 2.0f * Vec3(normals_.at(sp.uv)) - Vec3(1.0f);
  const float len = glm::length(n);
  if (!(len > 1e-6f) || !std::isfinite(len)) return Frame();
  Frame f;
  f.n = n / len;
  const Vec3 s = Vec3(1.0f, 0.0f, 0.0f) - f.n * f.n.x;  // dp/du is the local s axis
  const float ls = glm::length(s);
  if (!(ls > 1e-6f)) return Frame(f.n);
  f.s = s / ls;
  f.t = glm::cross(f.n, f.s);
  return f;
}

Color NormalMap::eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  const Frame f = frame(sp);
  const Vec3 wi_p = f.to_local(wi);
  if (!(wi.z * wi_p.z > 0.0f)) return Color(0.0f);
  const float scale = std::abs(wi_p.z) / std::abs(wi.z);  // 1 exactly for an untilted frame
  return nested_->eval(f.to_local(wo), wi_p, sp) * scale;
}

float NormalMap::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  const Frame f = frame(sp);
  const Vec3 wi_p = f.to_local(wi);
  if (!(wi.z * wi_p.z > 0.0f)) return 0.0f;
  return nested_->pdf(f.to_local(wo), wi_p, sp);
}

bool NormalMap::sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  const Frame f = frame(sp);
  if (!nested_->sample(f.to_local(wo), u, u_lobe, s, sp)) return false;
  const Vec3 wi = f.to_world(s.wi);
  if (!(wi.z * s.wi.z > 0.0f)) return false;
  s.wi = wi;  // weight and density carry over: the frames differ by a rotation
  return true;
}

int NormalMap::specular_lobes(const Vec3& wo, BsdfSample* out, const ShadingPoint& sp) const {
  const Frame f = frame(sp);
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

std::unique_ptr<Bsdf> NormalMap::create(const Params& p) {
  const ColorParam normals = p.texture("normalmap", Color(0.5f, 0.5f, 1.0f));
  if (normals.texture && normals.texture->channels() != 3) {
    p.fail("normalmap", "a normal map needs three channels (x, y, z as r, g, b); this texture has " +
                            std::to_string(normals.texture->channels()));
  }
  if (!normals.texture && !(glm::length(2.0f * Vec3(normals.value) - Vec3(1.0f)) > 1e-6f)) {
    p.fail("normalmap", "the normal 2 rgb - 1 is zero");
  }
  const std::vector<const Bsdf*> nested = p.bsdfs("bsdf", false);
  return std::make_unique<NormalMap>(nested.front(), normals);
}

}  // namespace caustica
