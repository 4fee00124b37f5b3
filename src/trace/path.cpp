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
  if (scene.has_media()) return trace_volume_path(camera_ray, scene, sampler, settings);
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

Color trace_volume_path(const Ray& camera_ray, const Scene& scene, Sampler& sampler, const MonteCarloSettings& settings) {
  // The path's throughput under spectral MIS over the whole path: EyePath::throughput().
  EyePath path{Color(0.0f), Color(1.0f), BsdfVertex{}, settings.max_depth, settings.hide_emitters, true};
  Color& L = path.L;
  Color& beta = path.beta;
  path.hero = std::min(int(sampler.next1d() * 3.0f), 2);
  int32_t medium = scene.camera_medium;
  Ray ray = camera_ray;
  int depth = 0;
  // Russian roulette after rr_depth vertices, as trace_path.
  auto survives = [&] {
    if (depth < settings.rr_depth) return true;
    const float survive = std::min(1.0f, max_component(path.throughput()));
    if (survive <= 0.0f || sampler.next1d() >= survive) return false;
    beta /= survive;
    return true;
  };
  // (Bounded: a path crossing null lobes without end stops.)
  for (int segment = 0; segment < 4 * (settings.max_depth + 1) + 256; ++segment) {
    SurfaceHit hit;
    float t = 0.0f;
    const EyePath::Step step = path.advance(scene, ray, medium, depth, sampler, hit, t);
    if (step == EyePath::Step::kEnd) break;
    if (step == EyePath::Step::kScattered) {
      // A medium vertex: direct light by a shadow ray, the path on by the phase function.
      if (depth >= settings.max_depth) break;
      const Vec3 p = ray.at(t), wo = -ray.dir;
      L += path.throughput() * estimate_direct_in_medium(scene, p, wo, medium, sampler, 1.0f);
      Vec3 wi;
      const float pdf = scene.media[size_t(medium)]->phase().sample(wo, sampler.next2d(), wi);
      if (!(pdf > 0.0f)) break;  // (the weight f / pdf is 1)
      path.from = BsdfVertex{false, pdf, p, Vec3(0.0f)};
      ray = Ray{p, wi, kInfinity};
      ++depth;
      if (!survives()) break;
      continue;
    }
    const Vec3 wo = -ray.dir;
    if (!hit.material->is_specular()) L += path.throughput() * estimate_direct(scene, hit, wo, sampler, 1.0f, medium);
    if (!path.scatter(hit, wo, sampler, ray)) break;
    if (hit.media) medium = hit.media->entered(ray.dir, hit.n);
    // A null lobe (straight through a thindielectric) is not a vertex, as Mitsuba's volpath counts.
    if (path.crossed_null) continue;
    ++depth;
    if (!survives()) break;
  }
  return L;
}

std::string PathIntegrator::describe() const {
  std::ostringstream s;
  s << "max_depth: " << settings_.max_depth << "\nrr_depth: " << settings_.rr_depth << "\n";
  if (settings_.hide_emitters) s << "hide_emitters: true\n";
  return s.str();
}

}  // namespace caustica
