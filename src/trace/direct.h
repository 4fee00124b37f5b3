// Next-event estimation: direct light at a diffuse surface point by shadow rays.
#pragma once
#include "core/sampler.h"
#include "core/scene.h"

namespace caustica {

// Reflected direct radiance towards wo (world) at a hit with non-delta lobes, from one light
// chosen by power and one point on it: f * Le * G * V / (p_light * pdf). With `mis`, weighted
// by the power heuristic against BSDF sampling (which must then count the emission it hits
// with mis_weight).
Color estimate_direct(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler, bool mis = false);

// The power heuristic (Veach 1997, beta = 2) for a sample of density pa against density pb.
inline float mis_weight(float pa, float pb) {
  const float a = pa * pa, b = pb * pb;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

}  // namespace caustica
