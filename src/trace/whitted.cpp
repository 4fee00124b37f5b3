// Whitted-style ray tracing: direct light by shadow rays, recursive mirror and glass,
// no indirect diffuse light (the course's renderer before Monte Carlo).
#include "trace/whitted.h"
#include <sstream>
#include "trace/direct.h"

namespace caustica {

std::unique_ptr<Integrator> WhittedIntegrator::create(const Params&, const RenderSettings& render) {
  return std::make_unique<WhittedIntegrator>(render.max_depth);
}

Color WhittedIntegrator::trace(const Ray& ray, const Scene& scene, Sampler& sampler, int depth) const {
  SurfaceHit hit;
  ++sampler.rays;
  if (!scene.intersect(ray, hit)) return scene.escaped(ray.dir);
  const Vec3 wo = -ray.dir;
  const Vec3 wo_l = hit.frame.to_local(wo);
  const Bsdf& m = *hit.material;
  Color L = scene.emitted(hit, wo_l);
  if (depth >= max_depth_) return L;  // max_depth 0: what the camera sees emit, only
  if (m.has(kBsdfDiffuse)) return L + estimate_direct(scene, hit, wo, sampler);
  if (depth + 1 >= max_depth_) return L;
  // Mirrors and glass, and glossy lobes in their specular limit: follow every branch,
  // weighted by Fresnel, as Whitted (1980) did.
  BsdfSample lobes[2];
  const int n = m.specular_lobes(wo_l, lobes, hit.sp);
  for (int i = 0; i < n; ++i) {
    if (is_black(lobes[i].weight)) continue;
    const Ray next = spawn_ray(hit.p, hit.n, hit.frame.to_world(lobes[i].wi));
    L += radiance_weight(m, wo_l, lobes[i], hit.sp) * trace(next, scene, sampler, depth + 1);
  }
  return L;
}

Color WhittedIntegrator::Li(const Ray& ray, const Scene& scene, Sampler& sampler) const {
  return trace(ray, scene, sampler, 0);
}

std::string WhittedIntegrator::describe() const {
  std::ostringstream s;
  s << "max_depth: " << max_depth_ << "\n";
  return s.str();
}

}  // namespace caustica
