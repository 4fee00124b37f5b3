// Render loop. Pixel (x, y), sample s seeds its own random stream from hash(pixel, s, seed),
// so neither tile order nor thread count changes the result; each pass is summed in order.
#include "trace/render.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
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

Image render_image(const Scene& scene, Integrator& integrator, const RenderOptions& options,
                   RenderStats& stats, std::vector<Image>* aovs) {
  const int w = scene.camera.width(), h = scene.camera.height();
  const int ts = options.tile_size;
  const int tiles_x = (w + ts - 1) / ts, tiles_y = (h + ts - 1) / ts;
  const int tile_count = tiles_x * tiles_y;
  const bool timed = options.time_limit > 0;
  std::vector<glm::dvec3> sum(size_t(w) * h, glm::dvec3(0.0));
  const bool want_aov = options.aov && aovs;
  constexpr int kA = Sampler::kAovCount;
  std::vector<float> aov_sum(want_aov ? size_t(w) * h * kA : 0, 0.0f);
  std::atomic<uint64_t> rays{0}, bad{0};
  std::atomic<int> tiles_done{0};
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  Progress progress("render", timed ? options.time_limit : double(options.spp) * tile_count, options.quiet);
  stats = RenderStats{};
  auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };

  const int crop_x = scene.camera.crop_x(), crop_y = scene.camera.crop_y();
  const uint64_t film_w = uint64_t(scene.camera.film_width());
  // Passes [p0, p1) of one tile, added to each pixel's sum in pass order: the sums are the same
  // whether a pass covers the image before the next begins or a tile runs all its passes.
  std::vector<int> pixel_passes(size_t(w) * h, 0);
  auto render_tile = [&](int tile, int p0, int p1) {
    const int x0 = (tile % tiles_x) * ts, y0 = (tile / tiles_x) * ts;
    uint64_t tile_rays = 0, tile_bad = 0;
    for (int pass = p0; pass < p1; ++pass) {
      if (cancelled()) break;
      for (int y = y0; y < std::min(y0 + ts, h); ++y) {
        for (int x = x0; x < std::min(x0 + ts, w); ++x) {
          const uint64_t pixel = uint64_t(y) * w + x;
          // Random streams follow the film pixel, so that a crop window renders the same
          // pixels as the whole film.
          const uint64_t film_pixel = uint64_t(y + crop_y) * film_w + uint64_t(x + crop_x);
          Sampler sampler(hash_seed(film_pixel, uint64_t(pass), options.seed));
          sampler.pixel = pixel;
          float aov[kA] = {};
          if (want_aov) sampler.aov = aov;
          Vec2 jitter = pixel_jitter(film_pixel, uint64_t(pass), options.seed);
          // Other filters than the box place the sample around the pixel's centre.
          if (!scene.render.filter.is_box()) jitter = Vec2(0.5f) + scene.render.filter.sample(jitter);
          // The lens sample comes first from the pixel's stream, only when there is a lens.
          const Ray ray = scene.camera.has_lens() ? scene.camera.generate_ray(x, y, jitter, sampler.next2d())
                                                  : scene.camera.generate_ray(x, y, jitter);
          Color L = integrator.Li(ray, scene, sampler);
          if (!is_finite(L) || L.r < 0 || L.g < 0 || L.b < 0) {
            L = Color(0.0f);
            ++tile_bad;
          }
          sum[pixel] += glm::dvec3(L);
          for (int a = 0; a < (want_aov ? kA : 0); ++a) aov_sum[pixel * kA + size_t(a)] += aov[a];
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
  auto finish_pass = [&](int passes) {
    stats.passes = passes;
    if (timed) progress.set(std::min(elapsed(), options.time_limit));
    if (options.on_pass) {
      Image mean(w, h);
      for (size_t i = 0; i < sum.size(); ++i) mean.pixels[i] = Color(sum[i] / double(passes));
      integrator.resolve(mean, pixel_passes);
      options.on_pass(passes, elapsed(), mean);
    }
  };
  const bool progressive = integrator.progressive();
  const PreprocessContext pass_context{options.seed, options.quiet, options.cancel};
  if (!timed && !options.on_pass && !progressive) {
    // A fixed pass count: each tile runs a group of passes, with a barrier only between groups
    // (an interrupted render keeps every finished pass; all tiles have started the group).
    constexpr int kGroup = 8;
    for (int p0 = 0; p0 < options.spp && !cancelled(); p0 += kGroup) {
      const int p1 = std::min(options.spp, p0 + kGroup);
      tbb::parallel_for(tbb::blocked_range<int>(0, tile_count), [&](const tbb::blocked_range<int>& range) {
        for (int tile = range.begin(); tile != range.end(); ++tile) render_tile(tile, p0, p1);
      });
    }
    stats.interrupted = cancelled();
    stats.passes = *std::min_element(pixel_passes.begin(), pixel_passes.end());
  } else {
    double last_pass_start = 0;
    for (int pass = 0;; ++pass) {
      if (!timed && pass >= options.spp) break;
      if (timed && pass > 0) {
        // The next pass would overrun the budget. The last pass's time counts too: a progressive
        // integrator's first photon pass ran before the render (preprocess), the others in it.
        const double t = elapsed();
        if (t + std::max(t / pass, t - last_pass_start) > options.time_limit) break;
      }
      last_pass_start = elapsed();
      if (progressive && !integrator.begin_pass(scene, pass, pass_context)) {
        stats.interrupted = true;
        stats.passes = pass;
        break;
      }
      tbb::parallel_for(tbb::blocked_range<int>(0, tile_count), [&](const tbb::blocked_range<int>& range) {
        for (int tile = range.begin(); tile != range.end(); ++tile) render_tile(tile, pass, pass + 1);
      });
      if (cancelled()) {
        stats.interrupted = true;
        // The cancel may have come after the last tile of this pass: then the pass is whole.
        // A pass cut short: the pixels it reached keep it (each pixel is divided by its own count).
        if (*std::min_element(pixel_passes.begin(), pixel_passes.end()) > pass) {
          finish_pass(pass + 1);
        } else {
          stats.passes = pass;
        }
        break;
      }
      finish_pass(pass + 1);
    }
  }
  progress.finish();
  stats.seconds = elapsed();
  stats.rays = rays;
  stats.bad_samples = bad;
  stats.samples = 0;
  // Each pixel is the mean of its own passes (after an interruption, some pixels have one more).
  Image image(w, h);
  if (want_aov) aovs->assign(2, Image(w, h));
  for (size_t i = 0; i < sum.size(); ++i) {
    stats.samples += uint64_t(pixel_passes[i]);
    if (pixel_passes[i] == 0) continue;
    const double inv = 1.0 / double(pixel_passes[i]);
    image.pixels[i] = Color(sum[i] * inv);
    if (want_aov) {
      (*aovs)[0].pixels[i] = Color(aov_sum[i * kA], aov_sum[i * kA + 1], 0.0f) * float(inv);
      (*aovs)[1].pixels[i] = Color(aov_sum[i * kA + 2], aov_sum[i * kA + 3], 0.0f) * float(inv);
    }
  }
  integrator.resolve(image, pixel_passes);
  return image;
}

}  // namespace caustica
