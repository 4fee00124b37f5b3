// Shared set-up for the kernel benchmarks: scenes, ray batches, photon maps.
#pragma once
#include <string>
#include <vector>
#include "core/scene_loader.h"
#include "photon/photon_map.h"

namespace caustica::bench {

std::string source_dir();
// Loads a scene file from scenes/, or the Stanford bunny from glmark2-data (null if missing).
const Scene* cornell_spheres();
const Scene* bunny();

struct RayBatch {
  std::vector<Ray> rays;  // shadow rays carry a finite tmax
};
// Rays from random points around the scene towards random points in it.
RayBatch make_rays(const Scene& scene, size_t n, bool shadow, uint64_t seed);

// Photons from a real photon pass on cornell-spheres (global map), at least n of them.
const std::vector<Photon>& cornell_photons(size_t n);

}  // namespace caustica::bench
