// The steps every eye path (path, photon, sppm) takes alike: meeting a surface with the
// emission found there, and continuing by a BSDF sample.
#pragma once
#include "core/media/medium.h"
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
  // For scenes without media: advance() with no medium.
  bool meet(const Scene& scene, const Ray& ray, int depth, Sampler& sampler, SurfaceHit& hit) {
    Ray r = ray;
    int32_t medium = -1;  // (a scene without media: advance() meets the first surface)
    float t = 0.0f;
    return advance(scene, r, medium, depth, sampler, hit, t) == Step::kSurface;
  }

  // In scenes with media (path's and sppm's eye paths): the channel free flights track and the
  // densities of the path's medium events per channel; the throughput under spectral MIS over
  // the path is throughput(), beta and r kept divided by r[hero] (take_medium_event).
  int hero = 0;
  Color r{1.0f};
  Color throughput() const { return hero_throughput(beta, r); }

  // In scenes with media: follows ray from eye vertex `depth` through `medium` (updated as it
  // crosses null boundaries, which are no vertices) to the next vertex, by a free flight in each
  // medium. kScattered: the flight scattered at ray.at(t) (with ray the segment it did so on);
  // kSurface: hit is a surface's, its emission added as meet() adds it; kEnd: the path ends (it
  // left the scene, nothing passed, depth is max_depth at a surface, or 256 boundaries crossed).
  enum class Step { kEnd, kScattered, kSurface };
  Step advance(const Scene& scene, Ray& ray, int32_t& medium, int depth, Sampler& sampler, SurfaceHit& hit, float& t) {
    const bool visible = !(hide_emitters && depth == 0);
    for (int crossings = 0; crossings < 256; ++crossings) {
      ++sampler.rays;
      const bool found = scene.intersect(ray, hit);
      if (medium >= 0) {
        const MediumEvent event = scene.media[size_t(medium)]->sample(ray, found ? hit.t : kInfinity, hero, sampler);
        if (!take_medium_event(event, hero, beta, r)) return Step::kEnd;
        if (event.scattered) {
          t = event.t;
          return Step::kScattered;
        }
      }
      if (!found) {
        if (visible) L += throughput() * escaped_mis(scene, ray.dir, from);
        return Step::kEnd;
      }
      if (Scene::is_medium_boundary(hit)) {
        Scene::cross(hit, ray, medium);
        continue;
      }
      if (visible) L += throughput() * emission_mis(scene, hit, scene.emitted(hit, hit.frame.to_local(-ray.dir)), from);
      return depth < max_depth ? Step::kSurface : Step::kEnd;
    }
    return Step::kEnd;
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
