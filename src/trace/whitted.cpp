// Whitted-style ray tracing: direct light by shadow rays, recursive mirror and glass,
// no indirect diffuse light (the course's renderer before Monte Carlo).
#include "trace/whitted.h"
#include <sstream>
#include "trace/direct.h"

namespace caustica {

WhittedIntegrator::WhittedIntegrator(const JsonSource& settings, const RenderSettings& render)
    : max_depth_(render.max_depth) {
  JsonReader r(settings.file);
  r.check_object(settings.value, settings.pointer, {});
}

Color WhittedIntegrator::trace(const Ray& ray, const Scene& scene, Sampler& sampler, int depth) const {
  SurfaceHit hit;
  ++sampler.rays;
  if (!scene.intersect(ray, hit)) return Color(0.0f);
  const Vec3 wo = -ray.dir;
  const Vec3 wo_l = hit.frame.to_local(wo);
  const Material& m = *hit.material;
  Color L = m.emitted(wo_l);
  if (m.is_diffuse()) return L + estimate_direct(scene, hit, wo, sampler);
  if (depth + 1 >= max_depth_) return L;
  const Vec3 refl = hit.frame.to_world(reflect_local(wo_l));
  if (const auto* glass = dynamic_cast<const Glass*>(&m)) {
    // Follow both branches, weighted by Fresnel, as Whitted (1980) did.
    const float F = glass->reflectance(wo_l);
    Vec3 wt;
    if (F < 1.0f && glass->refract(wo_l, wt)) {
      const Vec3 t = hit.frame.to_world(wt);
      L += (1.0f - F) * trace(spawn_ray(hit.p, hit.n, t), scene, sampler, depth + 1);
    }
    if (F > 0.0f) L += F * trace(spawn_ray(hit.p, hit.n, refl), scene, sampler, depth + 1);
    return L;
  }
  return L + m.albedo() * trace(spawn_ray(hit.p, hit.n, refl), scene, sampler, depth + 1);
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
