// Path tracing with next-event estimation and multiple importance sampling (power heuristic):
// at every vertex with a non-delta lobe, a shadow ray to one light, and emission reached by the
// BSDF sample weighted against it; after a delta bounce emission counts fully.
#include "trace/path.h"
#include <sstream>
#include "trace/direct.h"

namespace caustica {

PathIntegrator::PathIntegrator(const JsonSource& settings, const RenderSettings& render) {
  JsonReader r(settings.file, settings.sources);
  r.check_object(settings.value, settings.pointer, {"rr_depth", "hide_emitters"});
  settings_.max_depth = render.max_depth;
  if (settings.value.contains("hide_emitters")) {
    settings_.hide_emitters = r.boolean(settings.value["hide_emitters"], child(settings.pointer, "hide_emitters"));
  }
  if (settings.value.contains("rr_depth")) {
    settings_.rr_depth = int(r.integer(settings.value["rr_depth"], child(settings.pointer, "rr_depth"), 0, 1024));
  }
}

Color PathIntegrator::Li(const Ray& camera_ray, const Scene& scene, Sampler& sampler) const {
  Color L(0.0f), beta(1.0f);
  Ray ray = camera_ray;
  BsdfVertex from;  // the camera counts emission fully, as a delta bounce does
  // Paths have at most max_depth + 1 segments (Mitsuba's max_depth counts them): the segment
  // leaving vertex max_depth is traced for the emission it reaches, and ends the path there.
  for (int depth = 0; depth <= settings_.max_depth; ++depth) {
    SurfaceHit hit;
    ++sampler.rays;
    // Mitsuba's hide_emitters: what the camera sees directly of lights renders black.
    const bool visible = !(settings_.hide_emitters && depth == 0);
    if (!scene.intersect(ray, hit)) {
      if (visible) L += beta * escaped_mis(scene, ray.dir, from);
      break;
    }
    const Vec3 wo = -ray.dir;
    const Vec3 wo_l = hit.frame.to_local(wo);
    const Material& m = *hit.material;
    if (visible) L += beta * emission_mis(scene, hit, m.emitted(wo_l), from);
    if (depth == settings_.max_depth) break;
    if (!m.is_specular()) L += beta * estimate_direct(scene, hit, wo, sampler, 1.0f);
    BsdfSample bs;
    const Vec2 u = sampler.next2d();
    if (!m.sample(wo_l, u, sampler.next1d(), bs, hit.sp)) break;
    const Vec3 wi = hit.frame.to_world(bs.wi);
    if (hit.leaks(wi)) break;
    beta *= bs.weight;
    from = BsdfVertex{bs.delta, bs.pdf, hit.p};
    if (depth + 1 >= settings_.rr_depth) {
      const float survive = std::min(1.0f, max_component(beta));
      if (survive <= 0.0f || sampler.next1d() >= survive) break;
      beta /= survive;
    }
    ray = spawn_ray(hit.p, hit.n, wi);
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
