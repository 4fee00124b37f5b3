// Integrators against analytic answers: the furnace, and the factory's errors.
#include <catch2/catch.hpp>
#include <tbb/global_control.h>
#include "io/scene_loader.h"
#include "support/scenes.h"
#include "trace/render.h"

using namespace caustica;

namespace {
Color render_mean(const std::string& text, uint64_t seed = 0) {
  LoadedScene loaded = parse_scene(text, "furnace.json", ".");
  Scene& scene = *loaded.scene;
  auto integrator = create_integrator(loaded.integrator_type, loaded.integrator_settings, scene.render);
  integrator->preprocess(scene, {seed, true});
  RenderOptions options;
  options.job.passes = scene.render.spp;
  options.job.seed = seed;
  options.quiet = true;
  RenderStats stats;
  const Image image = render_image(scene, *integrator, options, stats);
  REQUIRE(stats.bad_samples == 0);
  return image.mean();
}
}  // namespace

TEST_CASE("path: furnace reads Le / (1 - albedo)", "[trace][furnace]") {
  for (double albedo : {0.5, 0.8}) {
    const Color mean = render_mean(test::furnace_scene(albedo, 1.0, R"({"type": "path"})", albedo > 0.6 ? 64 : 16));
    const double expected = 1.0 / (1.0 - albedo);
    INFO("albedo " << albedo << " mean " << mean.x << " " << mean.y << " " << mean.z);
    for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(expected).epsilon(0.01));
  }
}

TEST_CASE("whitted: furnace reads Le (1 + albedo): emission plus one diffuse bounce of direct light", "[trace][furnace]") {
  const Color mean = render_mean(test::furnace_scene(0.5, 1.0, R"({"type": "whitted"})", 16));
  for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(1.5).epsilon(0.01));
}

TEST_CASE("path: max_depth 1 sees emission only", "[trace]") {
  std::string text = test::furnace_scene(0.5, 1.0, R"({"type": "path"})", 2, 8);
  text.replace(text.find("\"max_depth\": 1000"), 17, "\"max_depth\": 1");
  const Color mean = render_mean(text);
  for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(1.5).epsilon(0.02));  // Le + direct at the first hit
}

TEST_CASE("integrator factory: unknown names and keys are errors", "[trace]") {
  RenderSettings rs;
  JsonSource src;
  src.file = "s.json";
  src.pointer = "/integrator";
  REQUIRE_THROWS_WITH(create_integrator("pathh", src, rs),
                      Catch::Contains("unknown integrator \"pathh\"") && Catch::Contains("path") &&
                          Catch::Contains("whitted"));
  src.value = {{"rr_dpth", 3}};
  REQUIRE_THROWS_WITH(create_integrator("path", src, rs),
                      Catch::Contains("s.json: /integrator/rr_dpth: unknown key") && Catch::Contains("rr_depth"));
  src.value = {{"rr_depth", -1}};
  REQUIRE_THROWS_WITH(create_integrator("path", src, rs), Catch::Contains("/integrator/rr_depth"));
}
