// Boundary correction for the volume photon maps. A density estimate with a ball of radius r
// loses the part of the ball outside the medium: next to a wall, a glass object or the shell of
// a bounded medium it holds fewer photons than the medium's density says, and volumetric photon
// mapping renders bounded media too dark (by a fifth on Mitsuba's media test scenes at the
// first radius). Each photon's kernel is instead normalised over the part of its ball that lies
// in its own medium and on its side of opaque surfaces, so that it spreads all its flux there
// (the correction of kernel estimates at a boundary; Silverman 1986, sec. 2.10).
#pragma once
#include <cstdint>
#include "core/rng.h"
#include "photon/volume_map.h"

namespace caustica {

class Scene;

// The fraction of the ball of `radius` around p that a ray from p along a direction reaches
// while in `medium`: surfaces that bound media without being there for light (null BSDFs,
// thindielectric's null lobe) are crossed, any other surface ends the direction. Estimated
// over `directions` stratified directions in a random orientation; in (0, 1]. `rays` counts
// the rays traced.
float medium_ball_fraction(const Scene& scene, const Vec3& p, int32_t medium, float radius, int directions, Rng& rng,
                           uint64_t& rays);

// The number of directions per photon, and the largest weight a photon takes (a photon in a
// sliver of medium far thinner than the radius).
constexpr int kBoundaryDirections = 16;
constexpr float kMaxBoundaryWeight = 16.0f;

// Multiplies each photon's power by 1 / its ball fraction at `radius` (at most
// kMaxBoundaryWeight); deterministic for any thread count (each photon's directions come from
// its index and `seed`). Returns the rays traced.
uint64_t correct_volume_boundaries(VolumePhotonMap& map, const Scene& scene, float radius, uint64_t seed);

}  // namespace caustica
