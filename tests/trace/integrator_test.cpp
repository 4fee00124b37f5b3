// Integrators against analytic answers: the furnace, and the factory's errors.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <tbb/global_control.h>
#include "io/scene_loader.h"
#include "support/scenes.h"
#include "support/render_util.h"
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

TEST_CASE("path: furnace reads Le / (1 - albedo)", "[trace][furnace]" TIER_UNIT) {
  for (double albedo : {0.5, 0.8}) {
    const Color mean = render_mean(test::furnace_scene(albedo, 1.0, R"({"type": "path"})", albedo > 0.6 ? 64 : 16));
    const double expected = 1.0 / (1.0 - albedo);
    INFO("albedo " << albedo << " mean " << mean.x << " " << mean.y << " " << mean.z);
    for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(expected).epsilon(0.01));
  }
}

TEST_CASE("whitted: furnace reads Le (1 + albedo): emission plus one diffuse bounce of direct light", "[trace][furnace]" TIER_UNIT) {
  const Color mean = render_mean(test::furnace_scene(0.5, 1.0, R"({"type": "whitted"})", 16));
  for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(1.5).epsilon(0.01));
}

TEST_CASE("path: max_depth 1 sees emission only", "[trace]" TIER_UNIT) {
  std::string text = test::furnace_scene(0.5, 1.0, R"({"type": "path"})", 2, 8);
  text.replace(text.find("\"max_depth\": 1000"), 17, "\"max_depth\": 1");
  const Color mean = render_mean(text);
  for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(1.5).epsilon(0.02));  // Le + direct at the first hit
}

TEST_CASE("integrator factory: unknown names and keys are errors", "[trace]" TIER_UNIT) {
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

TEST_CASE("max_depth 0: every integrator renders only the emitters the camera sees", "[trace]" TIER_UNIT) {
  // Mitsuba's max_depth 1: the camera ray's emission and nothing else.
  std::string scene = test::read_scene_file("scenes/cornell-box.json");
  scene.replace(scene.find("\"render\": {"), std::string("\"render\": {").size(), "\"render\": {\"max_depth\": 0, ");
  const auto path = test::render_text(scene, "path", "{}", 4, 32, 32);
  int lit = 0;
  for (const Color& c : path.image.pixels) {
    // The light's emission (17, 12, 4) or nothing.
    const bool light = c.x > 0.0f;
    lit += light;
    if (light) CHECK(c.x == Approx(17.0f * c.z / 4.0f).epsilon(1e-4));
    else CHECK(c == Color(0.0f));
  }
  CHECK(lit > 0);
  const char* runs[][2] = {{"photon", R"({"photons": 2000, "caustic_photons": 2000})"}, {"sppm", R"({"photons": 2000})"}, {"whitted", "{}"}};
  for (const auto& run : runs) {
    const char* integrator = run[0];
    INFO(integrator);
    const auto r = test::render_text(scene, integrator, run[1], 4, 32, 32);
    CHECK(test::region_mean(r.image, 0, 0, 32, 32).x == Approx(test::region_mean(path.image, 0, 0, 32, 32).x).epsilon(1e-5));
  }
}
