// Path tracing with next-event estimation (no MIS): emission is counted when seen by the
// camera or through delta bounces; after a diffuse bounce it came from the shadow ray.
#include "trace/path.h"
#include <sstream>
#include "trace/direct.h"

namespace caustica {

PathIntegrator::PathIntegrator(const JsonSource& settings, const RenderSettings& render) {
  JsonReader r(settings.file);
  r.check_object(settings.value, settings.pointer, {"rr_depth"});
  settings_.max_depth = render.max_depth;
  if (settings.value.contains("rr_depth")) {
    settings_.rr_depth = int(r.integer(settings.value["rr_depth"], child(settings.pointer, "rr_depth"), 0, 1024));
  }
}

Color PathIntegrator::Li(const Ray& camera_ray, const Scene& scene, Sampler& sampler) const {
  Color L(0.0f), beta(1.0f);
  Ray ray = camera_ray;
  bool count_emission = true;
  for (int depth = 0; depth < settings_.max_depth; ++depth) {
    SurfaceHit hit;
    ++sampler.rays;
    if (!scene.intersect(ray, hit)) break;
    const Vec3 wo = -ray.dir;
    const Vec3 wo_l = hit.frame.to_local(wo);
    const Material& m = *hit.material;
    if (count_emission) L += beta * m.emitted(wo_l);
    if (m.is_diffuse()) L += beta * estimate_direct(scene, hit, wo, sampler);
    BsdfSample bs;
    const Vec2 u = sampler.next2d();
    if (!m.sample(wo_l, u, sampler.next1d(), bs)) break;
    beta *= bs.weight;
    count_emission = bs.delta;
    if (depth + 1 >= settings_.rr_depth) {
      const float survive = std::min(1.0f, max_component(beta));
      if (survive <= 0.0f || sampler.next1d() >= survive) break;
      beta /= survive;
    }
    const Vec3 wi = hit.frame.to_world(bs.wi);
    ray = spawn_ray(hit.p, hit.n, wi);
  }
  return L;
}

std::string PathIntegrator::describe() const {
  std::ostringstream s;
  s << "max_depth: " << settings_.max_depth << "\nrr_depth: " << settings_.rr_depth << "\n";
  return s.str();
}

}  // namespace caustica
