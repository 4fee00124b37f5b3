// The render loop: passes of one sample per pixel over 16 px tiles with tbb::parallel_for.
#pragma once
#include <atomic>
#include <functional>
#include "core/image.h"
#include "trace/cluster.h"
#include "trace/integrator.h"

namespace caustica {

// What one render is asked for: the seed of all its random numbers, its passes (one sample per
// pixel each) and its time budget. A command makes one (render_job) and hands its seed to the
// integrator's preprocess too.
struct RenderJob {
  uint64_t seed = 0;
  int passes = 16;         // samples per pixel
  double time_budget = 0;  // seconds; > 0 renders whole passes until the budget is spent
};
// The scene's seed and samples per pixel (command-line overrides included), and a budget.
inline RenderJob render_job(const RenderSettings& rs, double time_budget = 0) { return {rs.seed, rs.spp, time_budget}; }

struct RenderOptions {
  RenderJob job;
  bool quiet = false;
  int tile_size = 16;
  const std::atomic<bool>* cancel = nullptr;  // set (e.g. by SIGINT) to stop after this tile
  bool aov = false;  // collect the integrator's per-sample AOVs (Sampler::aov)
  // The processes rendering this image (null: this one alone). Rank r of N renders passes
  // r, r + N, ...; rank 0 receives the image and the statistics of all, the others an empty image.
  const Cluster* cluster = nullptr;
  // Called on rank 0 after each completed pass (under MPI: round of passes) with the running
  // mean of all ranks' passes; may be null. With want_pass, only after the passes for which
  // want_pass(seconds), called on rank 0, is true: each call gathers the ranks' images. Set
  // on_pass on every rank (the others take part in the gathering).
  std::function<void(int passes, double seconds, const Image& mean)> on_pass;
  std::function<bool(double seconds)> want_pass;
};

struct RenderStats {
  double seconds = 0;
  uint64_t samples = 0;  // camera samples
  uint64_t rays = 0;     // all rays traced, shadow rays included
  int passes = 0;
  uint64_t bad_samples = 0;  // NaN, infinite or negative radiance, dropped
  bool interrupted = false;
  double gather_seconds = 0;  // MPI: summing the ranks' images on rank 0 (in `seconds`)
};

// Deterministic: the image for a scene, integrator and seed is the same for any thread count and
// any number of ranks (pixel sums are exact: core/fixed_sum.h).
// Sub-pixel position of sample `sample` of a pixel: a per-pixel rotation of the R2 sequence.
Vec2 pixel_jitter(uint64_t pixel, uint64_t sample, uint64_t seed);

// Refuses (InputError) a film whose sums, image and output copy would not fit in the memory this
// process may take (core/memory.h); render_image checks it too, but a caller can check before a
// long preprocess.
void check_film_memory(int width, int height, bool aov);

// With options.aov, `aovs` receives the per-pixel mean of the AOVs: two images, the first
// holding Sampler::aov[0..1] in red and green, the second aov[2..3].
Image render_image(const Scene& scene, Integrator& integrator, const RenderOptions& options,
                   RenderStats& stats, std::vector<Image>* aovs = nullptr);

}  // namespace caustica
