// Next-event estimation shared by the whitted, path and photon integrators.
#include "trace/direct.h"
#include "core/media/homogeneous.h"
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
                                 float mis_ratio, int32_t medium) const {
  if (i >= count_) return estimate_direct(scene, hit, wo, sampler, mis_ratio, medium);
  return estimate_direct(scene, hit, wo, u_light_[i], u_[i], sampler, mis_ratio, medium);
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
  const Color f = hit.material->eval(wo_l, wi_l, hit.sp) * radiance_scale(*hit.material, wo_l, wi_l, hit.sp);
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

Color direct_in_medium_mis(const Scene& scene, const Vec3& p, const Vec3& wo, int32_t medium, Sampler& sampler) {
  Color L = estimate_direct_in_medium(scene, p, wo, medium, sampler, 1.0f);
  Vec3 wi;
  const float pdf = scene.media[size_t(medium)]->phase().sample(wo, sampler.next2d(), wi);
  if (!(pdf > 0.0f)) return L;  // (the sample's weight f / pdf is 1)
  const BsdfVertex from{false, pdf, p, Vec3(0.0f)};
  SurfaceHit hit;
  Color tr;
  ++sampler.rays;
  if (scene.walk(Ray{p, wi, kInfinity}, medium, sampler, tr, hit)) {
    if (hit.light >= 0) L += tr * emission_mis(scene, hit, scene.emitted(hit, hit.frame.to_local(-wi)), from);
  } else if (!is_black(tr)) {
    L += tr * escaped_mis(scene, wi, from);
  }
  return L;
}

namespace {
// The part [ta, tb] of [0, tmax] of ray inside the cone {x : angle(x - apex, axis) <= acos(cos_theta)}
// (cos_theta > 0: one nappe, convex, so the part is one interval); false when empty.
bool clip_to_cone(const Ray& ray, float tmax, const Vec3& apex, const Vec3& axis, float cos_theta, float& ta,
                  float& tb) {
  const float far = std::isfinite(tmax) ? tmax : 1e8f;
  const Vec3 w = ray.origin - apex;
  const float c2 = cos_theta * cos_theta;
  const float dv = glm::dot(ray.dir, axis), wv = glm::dot(w, axis);
  auto inside = [&](float t) {
    const Vec3 x = w + t * ray.dir;
    const float along = glm::dot(x, axis);
    return along >= 0.0f && along * along >= c2 * glm::dot(x, x);
  };
  // The roots of (dv t + wv)^2 - c2 |w + t d|^2 split [0, far] into pieces wholly in or out.
  const double qa = double(dv) * dv - c2, qb = 2.0 * (double(dv) * wv - c2 * double(glm::dot(ray.dir, w))),
               qc = double(wv) * wv - c2 * double(glm::dot(w, w));
  float cuts[4] = {0.0f, far, 0.0f, 0.0f};
  int n = 2;
  if (std::abs(qa) > 1e-12) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      for (double root : {(-qb - r) / (2.0 * qa), (-qb + r) / (2.0 * qa)})
        if (root > 0.0 && root < far) cuts[n++] = float(root);
    }
  } else if (std::abs(qb) > 1e-12) {
    const double root = -qc / qb;
    if (root > 0.0 && root < far) cuts[n++] = float(root);
  }
  std::sort(cuts, cuts + n);
  ta = kInfinity, tb = -kInfinity;
  for (int i = 0; i + 1 < n; ++i) {
    if (!(cuts[i + 1] > cuts[i]) || !inside(0.5f * (cuts[i] + cuts[i + 1]))) continue;
    ta = std::min(ta, cuts[i]);
    tb = std::max(tb, cuts[i + 1]);
  }
  if (tb >= far && !std::isfinite(tmax)) tb = kInfinity;
  return tb > ta;
}
}  // namespace

namespace {
// Equiangular distance sampling (Kulla and Fajardo 2012) along [lo, hi] of ray towards point c:
// t = t0 + D tan(theta), theta uniform between the ends as seen from c; density
// D / ((theta_b - theta_a) (D^2 + (t - t0)^2)). False where the range is empty.
bool sample_equiangular(const Ray& ray, float lo, float hi, const Vec3& c, float u, float& t, float& pdf) {
  const float t0 = glm::dot(c - ray.origin, ray.dir);
  const float D = std::max(glm::length(c - ray.at(t0)), 1e-6f * (1.0f + std::abs(t0)));
  const float theta_a = std::atan2(lo - t0, D);
  const float theta_b = std::isfinite(hi) ? std::atan2(hi - t0, D) : 0.5f * kPi;
  if (!(theta_b > theta_a)) return false;
  const float theta = theta_a + u * (theta_b - theta_a);
  t = std::clamp(t0 + D * std::tan(theta), lo, hi);
  const float h = t - t0;
  pdf = D / ((theta_b - theta_a) * (D * D + h * h));
  return pdf > 0.0f;
}

// The radiance an area light sends to x (in `medium`) and x scatters towards wo, by two samples
// under MIS (power heuristic): a point of the light (sample_li) and a phase-function direction
// that reaches the light's surface (past the surfaces shadow rays pass). Each stays
// bounded where x nears the light, where the point alone (cos / d^2 over an area density)
// does not.
Color area_light_at(const Scene& scene, const Light& light, const Vec3& x, const Vec3& wo, int32_t medium,
                    const PhaseFunction& phase, Sampler& sampler) {
  Color L(0.0f);
  const Vec2 u_light = sampler.next2d(), u_phase = sampler.next2d();
  LightSample ls;
  if (light.sample_li(x, u_light, ls) && ls.pdf > 0.0f && !is_black(ls.weight)) {
    const float f = phase.eval(wo, ls.wi);
    if (f > 0.0f) {
      ++sampler.rays;
      const Color tr = scene.transmittance(spawn_ray_to(x, Vec3(0.0f), ls.p, ls.n), medium, sampler);
      L += tr * ls.weight * (f * mis_weight(ls.pdf, f));
    }
  }
  Vec3 wi;
  const float f = phase.sample(wo, u_phase, wi);
  if (!(f > 0.0f)) return L;
  // The phase sample: the first surface it meets past the media's boundaries, with the
  // transmittance to it (one walk: Scene::walk).
  SurfaceHit hit;
  Color tr;
  ++sampler.rays;
  if (!scene.walk(Ray{x, wi, kInfinity}, medium, sampler, tr, hit) || hit.light < 0 ||
      scene.lights[size_t(hit.light)].get() != &light)
    return L;
  const Color Le = scene.emitted(hit, hit.frame.to_local(-wi));
  if (is_black(Le) || is_black(tr)) return L;
  const float pdf_light = light.pdf_li(x, hit.p, hit.n);
  return L + tr * Le * mis_weight(f, pdf_light);  // (the phase sample's weight f / f is 1)
}
}  // namespace

Color single_scattering(const Scene& scene, const Ray& ray, float tmax, int32_t medium, const Color& sigma_t,
                        const Color& sigma_s, Sampler& sampler, const Light* end_light) {
  const float u_light = sampler.next1d();
  const Vec2 u = sampler.next2d();
  const float u_t = sampler.next1d();
  // By power and uniformly (Scene::sample_light_defensive): the light sampler's choice at one
  // point (the ray's origin) would miss a spot whose cone the segment crosses farther on.
  float pmf = 0.0f;
  const Light* light = scene.sample_light_defensive(u_light, pmf);
  if (!light || !(pmf > 0.0f)) return Color(0.0f);
  const PhaseFunction& phase = scene.media[size_t(medium)]->phase();
  const Vec3 wo = -ray.dir;
  float t = 0.0f, pdf_t = 0.0f;
  Color incident(0.0f);  // radiance arriving at t from the light's point over its densities
  Vec3 wi, to, to_n(0.0f);
  if (light->is_infinite()) {
    const float mean_t = (sigma_t.x + sigma_t.y + sigma_t.z) / 3.0f;
    if (!(mean_t > 0.0f)) return Color(0.0f);
    const float keep = std::isfinite(tmax) ? -std::expm1(-mean_t * tmax) : 1.0f;
    t = -std::log1p(-u_t * keep) / mean_t;
    pdf_t = mean_t * std::exp(-mean_t * t) / keep;
    LightSample ls;
    if (!(t < tmax) || !light->sample_li(ray.at(t), u, ls)) return Color(0.0f);
    wi = ls.wi, to = ls.p, to_n = ls.n, incident = ls.weight;
  } else if (light == end_light && !light->is_delta()) {
    // The area light the segment ends on: t sampled towards a point of it (which only guides
    // the distance: the estimate is unbiased whatever the point), then its light at t under MIS
    // (area_light_at). The point's own light (below) would weigh cos / d^2 over an area density
    // where t nears the segment's end on the light: specks. Elsewhere it is the better one (its
    // distance density cancels the 1 / d^2 of the very point).
    const LightPoint guide = light->sample_origin(u);
    if (!(guide.pdf > 0.0f) || !sample_equiangular(ray, 0.0f, tmax, guide.p, u_t, t, pdf_t)) return Color(0.0f);
    const Color at = area_light_at(scene, *light, ray.at(t), wo, medium, phase, sampler);
    return beer_lambert(sigma_t, t) * sigma_s * at / (pmf * pdf_t);
  } else {
    const LightPoint lp = light->sample_origin(u);
    if (!(lp.pdf > 0.0f)) return Color(0.0f);
    // A spot sends nothing outside its cone: t is sampled only where the ray is inside it.
    float lo = 0.0f, hi = tmax;
    // (Delta lights alone: an area light's bounds loop over its triangles.)
    const LightBounds lb = light->is_delta() ? light->light_bounds() : LightBounds{};
    if (lb.cos_theta_e >= 1.0f && lb.normals.cos_theta > 0.0f && lb.bounds.lo == lb.bounds.hi &&
        !clip_to_cone(ray, tmax, lb.bounds.lo, lb.normals.axis, lb.normals.cos_theta, lo, hi))
      return Color(0.0f);
    if (!sample_equiangular(ray, lo, hi, lp.p, u_t, t, pdf_t)) return Color(0.0f);
    const Vec3 d = lp.p - ray.at(t);
    const float dist2 = glm::dot(d, d);
    if (!(dist2 > 0.0f)) return Color(0.0f);
    wi = d / std::sqrt(dist2);
    to = lp.p, to_n = lp.n;
    incident = light->emitted_towards(lp, -wi) / (dist2 * lp.pdf);
  }
  if (!(pdf_t > 0.0f) || is_black(incident)) return Color(0.0f);
  const float f = phase.eval(wo, wi);
  if (!(f > 0.0f)) return Color(0.0f);
  ++sampler.rays;
  const Vec3 x = ray.at(t);
  const Color tr = scene.transmittance(spawn_ray_to(x, Vec3(0.0f), to, to_n), medium, sampler);
  if (is_black(tr)) return Color(0.0f);
  return beer_lambert(sigma_t, t) * sigma_s * tr * incident * (f / (pmf * pdf_t));
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
