// Whitted-style ray tracing: direct light by shadow rays, recursive mirror and glass,
// no indirect diffuse light (the course's renderer before Monte Carlo). In participating media,
// the media's analogue of the direct light at a diffuse surface: light scattered once towards
// the eye along each ray segment (single scattering), and the transmittance to what lies
// beyond.
#include "trace/whitted.h"
#include <sstream>
#include "core/media/homogeneous.h"
#include "trace/direct.h"

namespace caustica {

std::unique_ptr<Integrator> WhittedIntegrator::create(const Params&, const RenderSettings& render) {
  return std::make_unique<WhittedIntegrator>(render.max_depth);
}

bool WhittedIntegrator::through_medium(const Ray& ray, float s, const SurfaceHit* end, const Scene& scene,
                                       int32_t medium, Sampler& sampler, int depth, Color& L, Color& beta) const {
  const Medium& med = *scene.media[size_t(medium)];
  Color sigma_t, sigma_s;
  if (med.homogeneous(sigma_t, sigma_s)) {
    // In closed form: single scattering from a point sampled towards a light, Beer-Lambert.
    if (!is_black(sigma_s) && depth < max_depth_) {
      const Light* end_light = end && end->light >= 0 ? scene.lights[size_t(end->light)].get() : nullptr;
      L += beta * single_scattering(scene, ray, s, medium, sigma_t, sigma_s, sampler, end_light);
    }
    beta *= beer_lambert(sigma_t, s);
    return !is_black(beta);
  }
  // A grid medium: a delta-tracked flight either scatters (a shadow ray there, and the segment
  // ends) or passes; one-sample MIS over the tracked channel, chosen afresh per flight.
  const int hero = std::min(int(sampler.next1d() * 3.0f), 2);
  const MediumEvent event = med.sample(ray, s, hero, sampler);
  const float pdf = event.flight_pdf(hero);
  if (!(pdf > 0.0f)) return false;
  if (event.scattered) {
    if (depth < max_depth_)
      L += beta * event.weight / pdf * direct_in_medium_mis(scene, ray.at(event.t), -ray.dir, medium, sampler);
    return false;
  }
  beta *= event.weight / pdf;
  return !is_black(beta);
}

Color WhittedIntegrator::trace(Ray ray, const Scene& scene, Sampler& sampler, int depth, int32_t medium) const {
  Color L(0.0f), beta(1.0f);
  // (Bounded: a ray crossing medium boundaries without end, e.g. along a seam, stops.)
  for (int crossings = 0; crossings < 256; ++crossings) {
    SurfaceHit hit;
    ++sampler.rays;
    const bool found = scene.intersect(ray, hit);
    if (medium >= 0 &&
        !through_medium(ray, found ? hit.t : kInfinity, found ? &hit : nullptr, scene, medium, sampler, depth, L, beta))
      return L;
    if (!found) return L + beta * scene.escaped(ray.dir);
    if (Scene::is_medium_boundary(hit)) {  // not a bounce: the ray goes on in the other medium
      Scene::cross(hit, ray, medium);
      continue;
    }
    const Vec3 wo = -ray.dir;
    const Vec3 wo_l = hit.frame.to_local(wo);
    const Bsdf& m = *hit.material;
    L += beta * scene.emitted(hit, wo_l);
    if (depth >= max_depth_) return L;  // max_depth 0: what the camera sees emit, only
    if (m.has(kBsdfDiffuse)) return L + beta * estimate_direct(scene, hit, wo, sampler, 0.0f, medium);
    if (depth + 1 >= max_depth_) return L;
    // Mirrors and glass, and glossy lobes in their specular limit: follow every branch,
    // weighted by Fresnel, as Whitted (1980) did.
    BsdfSample lobes[2];
    const int n = m.specular_lobes(wo_l, lobes, hit.sp);
    for (int i = 0; i < n; ++i) {
      if (is_black(lobes[i].weight)) continue;
      const Vec3 wi = hit.frame.to_world(lobes[i].wi);
      const int32_t next = hit.media ? hit.media->entered(wi, hit.n) : medium;
      L += beta * radiance_weight(m, wo_l, lobes[i], hit.sp) *
           trace(spawn_ray(hit.p, hit.n, wi), scene, sampler, depth + 1, next);
    }
    return L;
  }
  return L;
}

Color WhittedIntegrator::Li(const Ray& ray, const Scene& scene, Sampler& sampler) const {
  return trace(ray, scene, sampler, 0, scene.camera_medium);
}

std::string WhittedIntegrator::describe() const {
  std::ostringstream s;
  s << "max_depth: " << max_depth_ << "\n";
  return s.str();
}

}  // namespace caustica
