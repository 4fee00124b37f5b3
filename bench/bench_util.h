// Shared set-up for the kernel benchmarks: scenes, ray batches, photon maps.
#pragma once
#include <atomic>
#include <memory>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <vector>
#include "io/scene_loader.h"
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

// Casts every ray of `rays` (Ray or RecordedRay) in parallel, in blocks of 4096 consecutive
// rays, with `cast(ray) -> bool`, and returns how many hit.
template <class R, class Cast>
size_t count_hits(const std::vector<R>& rays, Cast cast) {
  std::atomic<size_t> hits{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    size_t local = 0;
    for (size_t i = r.begin(); i != r.end(); ++i) local += cast(rays[i]) ? 1 : 0;
    hits += local;
  });
  return hits;
}

// The rays the path tracer casts on scenes/cornell-bunny.json at 1 spp, recorded on one thread
// in the order it casts them (null when the bunny is missing). `scene` renders it again.
struct RecordedRay {
  Ray ray;
  bool shadow = false;  // occluded() rather than intersect()
};
struct PathRays {
  std::unique_ptr<LoadedScene> loaded;
  std::vector<RecordedRay> rays;
  uint64_t samples = 0;  // camera samples of the recorded render
  Scene& scene() const { return *loaded->scene; }
};
const PathRays* cornell_bunny_path_rays();

// Photons from a real photon pass on cornell-spheres (global map), at least n of them.
const std::vector<Photon>& cornell_photons(size_t n);

}  // namespace caustica::bench
