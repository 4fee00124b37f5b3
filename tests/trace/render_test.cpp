// The render loop: determinism across thread counts, seeds, time budget, cancellation.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <tbb/global_control.h>
#include "io/scene_loader.h"
#include "trace/render.h"

using namespace caustica;

namespace {
struct Rendered {
  Image image;
  RenderStats stats;
};

Rendered render_tiny(const std::string& integrator_name, int threads, uint64_t seed, double time_limit = 0,
                     const std::atomic<bool>* cancel = nullptr) {
  LoadedScene loaded = load_scene(std::string(CAUSTICA_SOURCE_DIR) + "/tests/data/tiny.json");
  Scene& scene = *loaded.scene;
  JsonSource none;
  auto integrator = create_integrator(integrator_name, none, scene.render);
  tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(threads));
  integrator->preprocess(scene, {seed, true});
  RenderOptions options;
  options.job.passes = 8;
  options.job.seed = seed;
  options.quiet = true;
  options.job.time_budget = time_limit;
  options.tile_size = 8;
  options.cancel = cancel;
  Rendered r;
  r.image = render_image(scene, *integrator, options, r.stats);
  return r;
}
}  // namespace

TEST_CASE("render: same seed gives identical pixels with 1 and 2 threads", "[trace][determinism]" TIER_UNIT) {
  for (const char* name : {"path", "whitted"}) {
    const Rendered one = render_tiny(name, 1, 3);
    const Rendered two = render_tiny(name, 2, 3);
    REQUIRE(one.image.pixels.size() == two.image.pixels.size());
    CHECK(one.image.mean().x > 0.01f);  // not a black image
    bool identical = true;
    for (size_t i = 0; i < one.image.pixels.size(); ++i) identical = identical && one.image.pixels[i] == two.image.pixels[i];
    CHECK(identical);
    CHECK(one.stats.rays == two.stats.rays);
  }
}

TEST_CASE("render: another seed gives other noise but the same mean", "[trace]" TIER_UNIT) {
  const Rendered a = render_tiny("path", 2, 1), b = render_tiny("path", 2, 2);
  size_t differing = 0;
  for (size_t i = 0; i < a.image.pixels.size(); ++i) differing += a.image.pixels[i] != b.image.pixels[i];
  CHECK(differing > a.image.pixels.size() / 2);
  CHECK(a.image.mean().y == Approx(b.image.mean().y).epsilon(0.05));
}

TEST_CASE("render: a time budget renders whole passes", "[trace]" TIER_UNIT) {
  const Rendered r = render_tiny("path", 2, 0, 0.3);
  CHECK(r.stats.passes >= 1);
  CHECK(r.stats.samples == uint64_t(r.stats.passes) * 32 * 32);
  // It stops once the budget is spent (a time limit with no stop would never end).
  CHECK(r.stats.seconds < 5.0);
}

TEST_CASE("render: cancellation stops before the first pass completes and keeps no partial pass", "[trace]" TIER_UNIT) {
  std::atomic<bool> cancel{true};
  const Rendered r = render_tiny("path", 2, 0, 0, &cancel);
  CHECK(r.stats.interrupted);
  CHECK(r.stats.passes == 0);
  CHECK(r.image.mean().x == 0.0f);
}
