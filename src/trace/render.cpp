// Render loop. Pixel (x, y), sample s seeds its own random stream from hash(pixel, s, seed),
// and pixel sums are exact, so neither tile order, thread count nor rank count changes the result.
#include "trace/render.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include "core/memory.h"
#include "trace/progress.h"

namespace caustica {

Vec2 pixel_jitter(uint64_t pixel, uint64_t sample, uint64_t seed) {
  // R2 sequence (Roberts 2018), the plastic-number generalisation of the golden ratio,
  // rotated per pixel: any run of consecutive samples covers the pixel evenly, so edges
  // (the light's rim, silhouettes) converge at nearly 1/N instead of 1/sqrt(N).
  constexpr double a1 = 0.7548776662466927, a2 = 0.5698402909980532;
  Rng rng(hash_seed(pixel, seed, 0x6a6974746572ULL));  // "jitter"
  const double ox = rng.next_float(), oy = rng.next_float();
  const double x = ox + a1 * double(sample), y = oy + a2 * double(sample);
  return Vec2(float(x - std::floor(x)), float(y - std::floor(y)));
}

void check_film_memory(int width, int height, bool aov) {
  // Per pixel: three exact sums, a pass count, the mean image and the writer's copy of it; with
  // AOVs their sums and two more images.
  const double per_pixel = 3.0 * sizeof(FixedSum) + sizeof(int) + 2.0 * sizeof(Color) +
                           (aov ? Sampler::kAovCount * sizeof(FixedSum) + 2.0 * sizeof(Color) : 0.0);
  check_memory(double(width) * double(height) * per_pixel,
               "a " + std::to_string(width) + " x " + std::to_string(height) + " image", " (render a smaller image, or a crop)");
}

Image render_image(const Scene& scene, Integrator& integrator, const RenderOptions& options,
                   RenderStats& stats, std::vector<Image>* aovs) {
  const Cluster alone;
  const Cluster& cluster = options.cluster ? *options.cluster : alone;
  const int rank = cluster.rank(), ranks = cluster.size();
  const int w = scene.camera.width(), h = scene.camera.height();
  const int ts = options.tile_size;
  const int tiles_x = (w + ts - 1) / ts, tiles_y = (h + ts - 1) / ts;
  const int tile_count = tiles_x * tiles_y;
  const bool timed = options.job.time_budget > 0;
  check_film_memory(w, h, options.aov && aovs);
  // Exact sums (three per pixel): the same for any grouping of passes among threads and ranks.
  std::vector<FixedSum> sum(size_t(w) * h * 3, 0);
  const bool want_aov = options.aov && aovs;
  constexpr int kA = Sampler::kAovCount;
  std::vector<FixedSum> aov_sum(want_aov ? size_t(w) * h * kA : 0, 0);
  std::atomic<uint64_t> rays{0}, bad{0};
  std::atomic<int> tiles_done{0};
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // This rank's passes of a fixed count: rank, rank + ranks, ... below spp.
  const int own_passes = options.job.passes > rank ? (options.job.passes - rank + ranks - 1) / ranks : 0;
  Progress progress("render", timed ? options.job.time_budget : double(own_passes) * tile_count,
                    options.quiet || !cluster.root());
  stats = RenderStats{};
  auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };

  const int crop_x = scene.camera.crop_x(), crop_y = scene.camera.crop_y();
  const uint64_t film_w = uint64_t(scene.camera.film_width());
  // Passes p0, p0 + stride, ... below p1 of one tile, added to each pixel's sum.
  std::vector<int> pixel_passes(size_t(w) * h, 0);
  auto render_tile = [&](int tile, int p0, int p1, int stride) {
    const int x0 = (tile % tiles_x) * ts, y0 = (tile / tiles_x) * ts;
    uint64_t tile_rays = 0, tile_bad = 0;
    for (int pass = p0; pass < p1; pass += stride) {
      if (cancelled()) break;
      for (int y = y0; y < std::min(y0 + ts, h); ++y) {
        for (int x = x0; x < std::min(x0 + ts, w); ++x) {
          const uint64_t pixel = uint64_t(y) * w + x;
          // Random streams follow the film pixel, so that a crop window renders the same
          // pixels as the whole film.
          const uint64_t film_pixel = uint64_t(y + crop_y) * film_w + uint64_t(x + crop_x);
          Sampler sampler(hash_seed(film_pixel, uint64_t(pass), options.job.seed));
          sampler.pixel = pixel;
          float aov[kA] = {};
          if (want_aov) sampler.aov = aov;
          Vec2 jitter = pixel_jitter(film_pixel, uint64_t(pass), options.job.seed);
          // Other filters than the box place the sample around the pixel's centre; one with
          // negative lobes gives it a weight (negative where the filter is).
          if (!scene.render.filter.is_box()) jitter = Vec2(0.5f) + scene.render.filter.sample(jitter, &sampler.filter_weight);
          // The lens sample comes first from the pixel's stream, only when there is a lens.
          const Ray ray = scene.camera.has_lens() ? scene.camera.generate_ray(x, y, jitter, sampler.next2d())
                                                  : scene.camera.generate_ray(x, y, jitter);
          Color L = integrator.Li(ray, scene, sampler);
          if (!is_finite(L) || L.r < 0 || L.g < 0 || L.b < 0) {
            L = Color(0.0f);
            ++tile_bad;
          }
          L *= sampler.filter_weight;  // (the AOVs stay unweighted: filtered by |f|)
          for (int c = 0; c < 3; ++c) add_saturating(sum[pixel * 3 + size_t(c)], to_fixed(L[c]));
          for (int a = 0; a < (want_aov ? kA : 0); ++a) add_saturating(aov_sum[pixel * kA + size_t(a)], to_fixed(aov[a]));
          ++pixel_passes[pixel];
          tile_rays += sampler.rays;
        }
      }
      const int done = ++tiles_done;
      if (!timed) progress.set(done);
    }
    rays += tile_rays;
    bad += tile_bad;
  };
  // Each pixel is the mean of its own passes (after an interruption, some pixels have one more):
  // value c of pixel i, where `sums` holds `per_pixel` values a pixel.
  auto pixel_mean = [](const std::vector<FixedSum>& sums, const std::vector<int>& counts, size_t i,
                       size_t per_pixel, size_t c) {
    return float(from_fixed(sums[i * per_pixel + c]) * (1.0 / double(counts[i])));
  };
  auto mean_image = [&](const std::vector<FixedSum>& sums, const std::vector<int>& counts) {
    Image image(w, h);
    for (size_t i = 0; i < counts.size(); ++i) {
      if (counts[i] == 0) continue;
      image.pixels[i] = Color(pixel_mean(sums, counts, i, 3, 0), pixel_mean(sums, counts, i, 3, 1),
                              pixel_mean(sums, counts, i, 3, 2));
    }
    integrator.resolve(image, counts);
    return image;
  };
  // on_pass: the running mean of all ranks' passes, on rank 0, when every pixel has had the same
  // number of passes. A collective call: every rank makes it after each round.
  int reported = 0;
  auto report_pass = [&] {
    const bool wanted = cluster.root() && (!options.want_pass || options.want_pass(elapsed()));
    if (!cluster.any(wanted)) return;
    std::vector<FixedSum> sums_copy;
    std::vector<int> counts_copy;
    if (cluster.distributed()) {
      sums_copy = sum;
      counts_copy = pixel_passes;
      cluster.sum_to_root(sums_copy);
      cluster.sum_to_root(counts_copy);
      if (!cluster.root()) return;
    }
    const std::vector<FixedSum>& sums = cluster.distributed() ? sums_copy : sum;
    const std::vector<int>& counts = cluster.distributed() ? counts_copy : pixel_passes;
    const auto [fewest, most] = std::minmax_element(counts.begin(), counts.end());
    if (*fewest <= reported || *fewest != *most) return;  // no new pass, or one cut short
    reported = *fewest;
    options.on_pass(*fewest, elapsed(), mean_image(sums, counts));
  };
  const bool progressive = integrator.progressive();
  const PreprocessContext pass_context{options.job.seed, options.quiet || !cluster.root(), options.cancel, rank};
  bool stopped = false;  // a progressive pass's preparation was cancelled
  if (!timed && !options.on_pass && !progressive) {
    // A fixed pass count: each tile runs a group of this rank's passes, with a barrier only
    // between groups (an interrupted render keeps every finished pass).
    constexpr int kGroup = 8;
    for (int p0 = rank; p0 < options.job.passes && !cancelled(); p0 += kGroup * ranks) {
      const int p1 = std::min(options.job.passes, p0 + kGroup * ranks);
      tbb::parallel_for(tbb::blocked_range<int>(0, tile_count), [&](const tbb::blocked_range<int>& range) {
        for (int tile = range.begin(); tile != range.end(); ++tile) render_tile(tile, p0, p1, ranks);
      });
    }
  } else {
    // Rounds of one pass per rank: round k is passes kN .. kN + N - 1. Before each round the
    // ranks decide together whether to go on: rank 0's clock against the budget, and a stop
    // requested on any rank (Ctrl-C, SIGTERM), so that no rank renders a pass that is dropped.
    double last_round_start = 0;
    for (int round = 0;; ++round) {
      if (!timed && round * ranks >= options.job.passes) break;
      // A stop asked for on any rank; this call also waits for the slowest rank's last pass.
      if (cluster.any(cancelled() || stopped)) break;
      if (timed && round > 0) {
        // The next round would overrun the budget. The last round's time counts too: a progressive
        // integrator's first photon pass ran before the render (preprocess), the others in it.
        bool over = false;
        if (cluster.root()) {
          const double t = elapsed();
          over = t + std::max(t / round, t - last_round_start) > options.job.time_budget;
        }
        if (cluster.any(over)) break;
      }
      last_round_start = elapsed();
      const int pass = round * ranks + rank;
      // The last round of a fixed count may have no pass for some ranks.
      const bool mine = timed || pass < options.job.passes;
      if (mine && progressive && !integrator.begin_pass(scene, pass, pass_context)) stopped = true;
      if (mine && !stopped) {
        tbb::parallel_for(tbb::blocked_range<int>(0, tile_count), [&](const tbb::blocked_range<int>& range) {
          for (int tile = range.begin(); tile != range.end(); ++tile) render_tile(tile, pass, pass + 1, 1);
        });
      }
      if (timed) progress.set(std::min(elapsed(), options.job.time_budget));
      // Before the next round's go/stop: a cancel set in on_pass stops the next pass.
      if (options.on_pass) report_pass();
    }
  }
  progress.finish();
  stats.interrupted = cluster.any(cancelled() || stopped);
  // Rank 0 gathers the sums, the pass counts and the counters of all ranks (timed from when the
  // last rank is ready).
  cluster.barrier();
  const double gather_start = elapsed();
  cluster.sum_to_root(sum);
  cluster.sum_to_root(pixel_passes);
  if (want_aov) cluster.sum_to_root(aov_sum);
  std::vector<uint64_t> counters{rays.load(), bad.load()};
  cluster.sum_to_root(counters);
  stats.seconds = elapsed();
  stats.gather_seconds = stats.seconds - gather_start;
  if (!cluster.root()) return Image();
  stats.rays = counters[0];
  stats.bad_samples = counters[1];
  stats.passes = *std::min_element(pixel_passes.begin(), pixel_passes.end());
  stats.samples = 0;
  for (int n : pixel_passes) stats.samples += uint64_t(n);
  Image image = mean_image(sum, pixel_passes);
  if (want_aov) {
    aovs->assign(2, Image(w, h));
    for (size_t i = 0; i < pixel_passes.size(); ++i) {
      if (pixel_passes[i] == 0) continue;
      auto mean = [&](size_t a) { return pixel_mean(aov_sum, pixel_passes, i, kA, a); };
      (*aovs)[0].pixels[i] = Color(mean(0), mean(1), 0.0f);
      (*aovs)[1].pixels[i] = Color(mean(2), mean(3), 0.0f);
    }
  }
  return image;
}

}  // namespace caustica
