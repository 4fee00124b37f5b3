// Next-event estimation: direct light at a diffuse surface point by shadow rays.
#pragma once
#include "core/sampler.h"
#include "core/scene.h"

namespace caustica {

// Reflected direct radiance towards wo (world) at a hit with non-delta lobes, from one light
// chosen by the scene's light sampler and one point on it: f * Le * G * V / (p_light * pdf). With mis_ratio > 0,
// weighted by the power heuristic against BSDF sampling that takes mis_ratio samples per
// light sample (and must count the emission it hits with emission_mis / escaped_mis, its
// density scaled by the same ratio); 0 means no MIS.
// In a scene with media the shadow ray passes media boundaries and takes the transmittance,
// starting in `medium` (the ray's) unless the hit's surface bounds media itself.
Color estimate_direct(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler,
                      float mis_ratio = 0.0f, int32_t medium = -1);
// The same with the light chosen by u_light and its point by u.
Color estimate_direct(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, float u_light, const Vec2& u,
                      Sampler& sampler, float mis_ratio, int32_t medium = -1);
// The same at a scattering point p inside `medium`, its phase function in place of a BSDF.
Color estimate_direct_in_medium(const Scene& scene, const Vec3& p, const Vec3& wo, int32_t medium, Sampler& sampler,
                                float mis_ratio);

// The same by both strategies under MIS (power heuristic): a light sample (mis_ratio 1) and a
// phase sample whose walk through the media (Scene::walk) reaches an emitter or leaves the
// scene. For a point where a path ends (sppm's visible point, a flight's end in `photon` and
// `whitted`): bounded where p nears a light, where the light sample alone (cos / d^2 over an
// area density, of infinite variance in fog beneath a lamp) is not.
Color direct_in_medium_mis(const Scene& scene, const Vec3& p, const Vec3& wo, int32_t medium, Sampler& sampler);
// Single scattering towards -ray.dir along [0, tmax] (tmax may be infinite) of ray inside a
// homogeneous medium (sigma_t, sigma_s, its phase function): the integral of Tr(t) sigma_s
// times the light scattered at t, by one light (chosen by power or uniformly, half the time
// each: Scene::sample_light_defensive), one point on it, and t by equiangular sampling towards
// that point (Kulla and Fajardo 2012: the density follows 1 / distance^2, so a light close to
// the ray adds no fireflies), the shadow ray through the media from t. A light at infinity
// takes t by the mean extinction instead. `end_light`: the area light the segment ends on, if
// any; for it the point only guides t, and the light at t is a light sample and a phase sample
// under MIS (bounded where t nears the light's surface).
Color single_scattering(const Scene& scene, const Ray& ray, float tmax, int32_t medium, const Color& sigma_t,
                        const Color& sigma_s, Sampler& sampler, const Light* end_light = nullptr);

// n light samples at one point, stratified: the light's choice over n strata of [0, 1), the
// point on it over an sx x sy grid of [0, 1)^2 (the remainder unstratified), the two paired at
// random. With several samples at a point, the share that lands on a small bright light or a
// sun is then nearly fixed instead of binomial. One sample (or past kMax) draws as
// estimate_direct does.
class StratifiedDirect {
 public:
  static constexpr int kMax = 64;
  StratifiedDirect(Sampler& sampler, int n);
  // Sample i (0 .. n - 1) of estimate_direct.
  Color estimate(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler, int i,
                 float mis_ratio, int32_t medium = -1) const;

 private:
  int count_ = 0;  // samples with stored numbers
  float u_light_[kMax];
  Vec2 u_[kMax];
};

// The power heuristic (Veach 1997, beta = 2) for a sample of density pa against density pb.
inline float mis_weight(float pa, float pb) {
  const float a = pa * pa, b = pb * pb;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

// Where a path continues by BSDF sampling from a vertex that also sampled the lights: the
// previous vertex's state, for weighting the emission the continuation reaches.
struct BsdfVertex {
  bool specular = true;  // a delta bounce (or the camera): emission counts in full
  float pdf = 0.0f;      // solid-angle density of the BSDF sample, times its MIS sample ratio
  Vec3 p{0.0f};          // where it was taken
  Vec3 n{0.0f};          // the shading normal there (the light sampler's choice depends on both)
};

// Emission Le of a surface hit reached from `from`, weighted against next-event estimation.
Color emission_mis(const Scene& scene, const SurfaceHit& hit, const Color& Le, const BsdfVertex& from);
// The environment seen by a ray leaving the scene along dir, weighted likewise.
Color escaped_mis(const Scene& scene, const Vec3& dir, const BsdfVertex& from);

}  // namespace caustica
