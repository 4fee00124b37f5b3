// Next-event estimation shared by the whitted, path and photon integrators.
#include "trace/direct.h"
#include <algorithm>
#include <cmath>

namespace caustica {

Color estimate_direct(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler, float mis_ratio,
                      int32_t medium) {
  const float u_light = sampler.next1d();
  const Vec2 u = sampler.next2d();
  return estimate_direct(scene, hit, wo, u_light, u, sampler, mis_ratio, medium);
}

StratifiedDirect::StratifiedDirect(Sampler& sampler, int n) {
  if (n <= 1) return;
  n = count_ = std::min(n, kMax);
  const int sx = std::max(1, int(std::sqrt(float(n)))), sy = n / sx;
  int order[kMax];
  for (int i = 0; i < n; ++i) order[i] = i;
  for (int i = n - 1; i > 0; --i) std::swap(order[i], order[std::min(i, int(sampler.next1d() * float(i + 1)))]);
  for (int i = 0; i < n; ++i) {
    u_light_[i] = std::min((float(i) + sampler.next1d()) / float(n), 0x1.fffffep-1f);
    const int k = order[i];
    const Vec2 r = sampler.next2d();
    u_[i] = k < sx * sy ? Vec2(std::min((float(k % sx) + r.x) / float(sx), 0x1.fffffep-1f),
                              std::min((float(k / sx) + r.y) / float(sy), 0x1.fffffep-1f))
                       : r;
  }
}

Color StratifiedDirect::estimate(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler, int i,
                                 float mis_ratio) const {
  if (i >= count_) return estimate_direct(scene, hit, wo, sampler, mis_ratio);
  return estimate_direct(scene, hit, wo, u_light_[i], u_[i], sampler, mis_ratio);
}

namespace {
// The light u_light chooses for a point p (shading normal n, or zero in a medium) and the point
// u picks on it; false where there is none.
bool choose_light_point(const Scene& scene, const Vec3& p, const Vec3& n, float u_light, const Vec2& u, float& pmf,
                        LightSample& ls) {
  const Light* light = scene.sample_light(p, n, u_light, pmf);
  return light && pmf > 0.0f && light->sample_li(p, u, ls);
}
}  // namespace

Color estimate_direct(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, float u_light, const Vec2& u,
                      Sampler& sampler, float mis_ratio, int32_t medium) {
  float pmf = 0.0f;
  LightSample ls;
  if (!choose_light_point(scene, hit.p, hit.frame.n, u_light, u, pmf, ls)) return Color(0.0f);
  const Vec3 wo_l = hit.frame.to_local(wo), wi_l = hit.frame.to_local(ls.wi);
  if (hit.leaks(ls.wi)) return Color(0.0f);
  const Color f = hit.material->eval(wo_l, wi_l, hit.sp);
  if (is_black(f)) return Color(0.0f);
  ++sampler.rays;
  // (Without media, occluded() alone.)
  const Color tr = scene.transmittance(spawn_ray_to(hit.p, hit.n, ls.p, ls.n),
                                       hit.media ? hit.media->entered(ls.wi, hit.n) : medium, sampler);
  if (is_black(tr)) return Color(0.0f);
  float w = 1.0f;
  if (mis_ratio > 0.0f && ls.pdf > 0.0f) w = mis_weight(pmf * ls.pdf, mis_ratio * hit.material->pdf(wo_l, wi_l, hit.sp));
  return tr * f * ls.weight * (w * std::abs(wi_l.z) / pmf);
}

Color estimate_direct_in_medium(const Scene& scene, const Vec3& p, const Vec3& wo, int32_t medium, Sampler& sampler,
                                float mis_ratio) {
  const float u_light = sampler.next1d();
  const Vec2 u = sampler.next2d();
  float pmf = 0.0f;
  LightSample ls;
  if (!choose_light_point(scene, p, Vec3(0.0f), u_light, u, pmf, ls)) return Color(0.0f);
  const float f = scene.media[size_t(medium)]->phase().eval(wo, ls.wi);
  if (!(f > 0.0f)) return Color(0.0f);
  ++sampler.rays;
  const Color tr = scene.transmittance(spawn_ray_to(p, Vec3(0.0f), ls.p, ls.n), medium, sampler);
  if (is_black(tr)) return Color(0.0f);
  float w = 1.0f;
  if (mis_ratio > 0.0f && ls.pdf > 0.0f) w = mis_weight(pmf * ls.pdf, mis_ratio * f);
  return tr * ls.weight * (f * w / pmf);
}

Color emission_mis(const Scene& scene, const SurfaceHit& hit, const Color& Le, const BsdfVertex& from) {
  if (is_black(Le) || from.specular || hit.light < 0) return Le;
  const size_t i = size_t(hit.light);
  const float light_pdf = scene.light_pmf(from.p, from.n, i) * scene.lights[i]->pdf_li(from.p, hit.p, hit.n);
  return Le * mis_weight(from.pdf, light_pdf);
}

Color escaped_mis(const Scene& scene, const Vec3& dir, const BsdfVertex& from) {
  // Each environment light is weighted against its own light-sampling density, as
  // estimate_direct weighted it, so the weights add to 1 with several of them.
  Color L(0.0f);
  for (size_t i : scene.environment()) {
    const Color Le = scene.lights[i]->escaped(dir);
    L += from.specular ? Le : Le * mis_weight(from.pdf, scene.light_pmf(from.p, from.n, i) * scene.lights[i]->pdf_escaped(dir));
  }
  return L;
}

}  // namespace caustica
