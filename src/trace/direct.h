// Next-event estimation: direct light at a diffuse surface point by shadow rays.
#pragma once
#include "core/sampler.h"
#include "core/scene.h"

namespace caustica {

// Reflected direct radiance towards wo (world) at a diffuse hit, from one light chosen by
// power and one point on it: f * Le * G * V / (p_light * pdf).
Color estimate_direct(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler);

}  // namespace caustica
