// Path tracing with next-event estimation and multiple importance sampling (power heuristic):
// at every vertex with a non-delta lobe, a shadow ray to one light, and emission reached by the
// BSDF sample weighted against it; after a delta bounce emission counts fully.
#include "trace/path.h"
#include <sstream>
#include "trace/eye_path.h"

namespace caustica {

std::unique_ptr<Integrator> PathIntegrator::create(const Params& p, const RenderSettings& render) {
  return std::make_unique<PathIntegrator>(read_monte_carlo(p, render));
}

Color PathIntegrator::Li(const Ray& camera_ray, const Scene& scene, Sampler& sampler) const {
  return trace_path(camera_ray, scene, sampler, settings_);
}

Color trace_path(const Ray& camera_ray, const Scene& scene, Sampler& sampler, const MonteCarloSettings& settings) {
  EyePath path{Color(0.0f), Color(1.0f), BsdfVertex{}, settings.max_depth, settings.hide_emitters};
  Ray ray = camera_ray;
  for (int depth = 0;; ++depth) {
    SurfaceHit hit;
    if (!path.meet(scene, ray, depth, sampler, hit)) break;
    const Vec3 wo = -ray.dir;
    // Every vertex's shadow ray is weighted against its BSDF sample, which counts the emission
    // it reaches (on the last vertex too: see EyePath::meet).
    if (!hit.material->is_specular()) path.L += path.beta * estimate_direct(scene, hit, wo, sampler, 1.0f);
    if (!path.scatter(hit, wo, sampler, ray)) break;
    if (depth + 1 >= settings.rr_depth) {
      const float survive = std::min(1.0f, max_component(path.beta));
      if (survive <= 0.0f || sampler.next1d() >= survive) break;
      path.beta /= survive;
    }
  }
  return path.L;
}

std::string PathIntegrator::describe() const {
  std::ostringstream s;
  s << "max_depth: " << settings_.max_depth << "\nrr_depth: " << settings_.rr_depth << "\n";
  if (settings_.hide_emitters) s << "hide_emitters: true\n";
  return s.str();
}

}  // namespace caustica
