// The steps every eye path (path, photon, sppm) takes alike: meeting a surface with the
// emission found there, and continuing by a BSDF sample.
#pragma once
#include "core/sampler.h"
#include "core/scene.h"
#include "trace/direct.h"

namespace caustica {

struct EyePath {
  Color L{0.0f}, beta{1.0f};
  BsdfVertex from;  // the camera counts emission fully, as a delta bounce does
  int max_depth = 16;
  bool hide_emitters = false;  // Mitsuba's: what the camera sees directly of lights renders black
  // In scenes with media (Mitsuba's volpath) a null lobe (kBsdfNull: straight through a
  // thindielectric) is no vertex: shadow rays pass it (Scene::transmittance), so `from` stays
  // the vertex before it, and max_depth does not count it. crossed_null: the last scatter did so.
  bool transparent_nulls = false;
  bool crossed_null = false;

  // Intersects `ray` (the segment reaching eye vertex `depth`, 0 for the camera ray) and adds
  // the emission it finds, MIS-weighted against the previous vertex's shadow ray. False when the
  // path ends: the ray left the scene, or depth is max_depth. A path then has at most
  // max_depth + 1 segments, the last only for the emission it reaches (Mitsuba's max_depth).
  bool meet(const Scene& scene, const Ray& ray, int depth, Sampler& sampler, SurfaceHit& hit) {
    ++sampler.rays;
    const bool visible = !(hide_emitters && depth == 0);
    if (!scene.intersect(ray, hit)) {
      if (visible) L += beta * escaped_mis(scene, ray.dir, from);
      return false;
    }
    if (visible) L += beta * emission_mis(scene, hit, scene.emitted(hit, hit.frame.to_local(-ray.dir)), from);
    return depth < max_depth;
  }

  // Samples the BSDF at `hit` towards the next vertex; false when the path ends.
  bool scatter(const SurfaceHit& hit, const Vec3& wo, Sampler& sampler, Ray& ray) {
    BsdfSample bs;
    const Vec2 u = sampler.next2d();
    const Vec3 wo_l = hit.frame.to_local(wo);
    if (!hit.material->sample(wo_l, u, sampler.next1d(), bs, hit.sp)) return false;
    const Vec3 wi = hit.frame.to_world(bs.wi);
    if (hit.leaks(wi)) return false;
    beta *= radiance_weight(*hit.material, wo_l, bs, hit.sp);
    crossed_null = transparent_nulls && bs.null();
    if (!crossed_null) from = BsdfVertex{bs.delta, bs.pdf, hit.p, hit.frame.n};
    ray = spawn_ray(hit.p, hit.n, wi);
    return true;
  }
};

}  // namespace caustica
