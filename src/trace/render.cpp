// Render loop. Pixel (x, y), sample s seeds its own random stream from hash(pixel, s, seed),
// so neither tile order nor thread count changes the result; each pass is summed in order.
#include "trace/render.h"
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

Image render_image(const Scene& scene, const Integrator& integrator, const RenderOptions& options,
                   RenderStats& stats, std::vector<Image>* aovs) {
  const int w = scene.camera.width(), h = scene.camera.height();
  const int ts = options.tile_size;
  const int tiles_x = (w + ts - 1) / ts, tiles_y = (h + ts - 1) / ts;
  const int tile_count = tiles_x * tiles_y;
  const bool timed = options.time_limit > 0;
  std::vector<glm::dvec3> sum(size_t(w) * h, glm::dvec3(0.0));
  Image pass_image(w, h);
  const bool want_aov = options.aov && aovs;
  constexpr int kA = Sampler::kAovCount;
  std::vector<float> aov_pass(want_aov ? size_t(w) * h * kA : 0), aov_sum(aov_pass.size(), 0.0f);
  std::atomic<uint64_t> rays{0}, bad{0};
  std::atomic<int> tiles_done{0};
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  Progress progress("render", timed ? options.time_limit : double(options.spp) * tile_count, options.quiet);
  stats = RenderStats{};
  auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };

  const int crop_x = scene.camera.crop_x(), crop_y = scene.camera.crop_y();
  const uint64_t film_w = uint64_t(scene.camera.film_width());
  for (int pass = 0;; ++pass) {
    if (!timed && pass >= options.spp) break;
    if (timed && pass > 0) {
      const double t = elapsed();
      if (t + t / pass > options.time_limit) break;  // the next pass would overrun the budget
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, tile_count), [&](const tbb::blocked_range<int>& range) {
      for (int tile = range.begin(); tile != range.end(); ++tile) {
        if (cancelled()) return;
        const int x0 = (tile % tiles_x) * ts, y0 = (tile / tiles_x) * ts;
        uint64_t tile_rays = 0, tile_bad = 0;
        for (int y = y0; y < std::min(y0 + ts, h); ++y) {
          for (int x = x0; x < std::min(x0 + ts, w); ++x) {
            const uint64_t pixel = uint64_t(y) * w + x;
            // Random streams follow the film pixel, so that a crop window renders the same
            // pixels as the whole film.
            const uint64_t film_pixel = uint64_t(y + crop_y) * film_w + uint64_t(x + crop_x);
            Sampler sampler(hash_seed(film_pixel, uint64_t(pass), options.seed));
            if (want_aov) {
              sampler.aov = &aov_pass[pixel * kA];
              std::fill(sampler.aov, sampler.aov + kA, 0.0f);
            }
            const Vec2 jitter = pixel_jitter(film_pixel, uint64_t(pass), options.seed);
            const Ray ray = scene.camera.generate_ray(x, y, jitter);
            Color L = integrator.Li(ray, scene, sampler);
            if (!is_finite(L) || L.r < 0 || L.g < 0 || L.b < 0) {
              L = Color(0.0f);
              ++tile_bad;
            }
            pass_image.at(x, y) = L;
            tile_rays += sampler.rays;
          }
        }
        rays += tile_rays;
        bad += tile_bad;
        const int done = ++tiles_done;
        if (!timed) progress.set(done);
      }
    });
    if (cancelled()) {
      stats.interrupted = true;
      break;
    }
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += glm::dvec3(pass_image.pixels[i]);
    for (size_t i = 0; i < aov_sum.size(); ++i) aov_sum[i] += aov_pass[i];
    stats.passes = pass + 1;
    if (timed) progress.set(std::min(elapsed(), options.time_limit));
    if (options.on_pass) {
      Image mean(w, h);
      for (size_t i = 0; i < sum.size(); ++i) mean.pixels[i] = Color(sum[i] / double(stats.passes));
      options.on_pass(stats.passes, elapsed(), mean);
    }
  }
  progress.finish();
  stats.seconds = elapsed();
  stats.rays = rays;
  stats.bad_samples = bad;
  stats.samples = uint64_t(stats.passes) * w * h;
  Image image(w, h);
  if (stats.passes > 0) {
    for (size_t i = 0; i < sum.size(); ++i) image.pixels[i] = Color(sum[i] / double(stats.passes));
  }
  if (want_aov) {
    aovs->assign(2, Image(w, h));
    const float inv = stats.passes > 0 ? 1.0f / float(stats.passes) : 0.0f;
    for (size_t i = 0; i < size_t(w) * h; ++i) {
      (*aovs)[0].pixels[i] = Color(aov_sum[i * kA], aov_sum[i * kA + 1], 0.0f) * inv;
      (*aovs)[1].pixels[i] = Color(aov_sum[i * kA + 2], aov_sum[i * kA + 3], 0.0f) * inv;
    }
  }
  return image;
}

}  // namespace caustica
