// Next-event estimation: stratified light samples.
#include <catch2/catch.hpp>
#include <set>
#include "io/scene_loader.h"
#include "trace/direct.h"
#include "support/scenes.h"

using namespace caustica;

TEST_CASE("direct: stratified light samples choose each of n equal lights exactly once", "[trace][direct]") {
  // Four point lights of equal power around a floor point: with 4 stratified samples each light
  // is chosen once, so the estimate is the exact sum every time (independent samples vary).
  const std::string scene_text = test::floor_scene(R"({"type": "point", "position": [1, 1, 0], "intensity": [1, 1, 1]},
               {"type": "point", "position": [-1, 2, 0], "intensity": [1, 1, 1]},
               {"type": "point", "position": [0, 3, 1], "intensity": [1, 1, 1]},
               {"type": "point", "position": [0, 1.5, -2], "intensity": [1, 1, 1]})");
  LoadedScene loaded = parse_scene(scene_text, "test.json", ".");
  // (Chosen by power, the four have equal chances; the light tree would weigh them by distance.)
  loaded.scene->render.light_sampler = LightSamplerKind::Power;
  loaded.scene->build(loaded.scene->accel().primitives());
  const Scene& scene = *loaded.scene;
  SurfaceHit hit;
  REQUIRE(scene.intersect(Ray{Vec3(0, 4, 0), Vec3(0, -1, 0)}, hit));
  const Vec3 wo(0, 1, 0);
  // The exact direct light: rho / pi * sum I cos / d^2.
  double exact = 0;
  for (const Vec3 p : {Vec3(1, 1, 0), Vec3(-1, 2, 0), Vec3(0, 3, 1), Vec3(0, 1.5, -2)}) {
    const double d2 = double(glm::dot(p, p));
    exact += 0.5 / kPi * double(p.y) / std::sqrt(d2) / d2;
  }
  double spread_stratified = 0, spread_independent = 0, mean_independent = 0;
  constexpr int kTrials = 200;
  for (int t = 0; t < kTrials; ++t) {
    Sampler sampler(hash_seed(uint64_t(t), 1000));
    const StratifiedDirect lights(sampler, 4);
    double stratified = 0, independent = 0;
    for (int i = 0; i < 4; ++i) {
      stratified += double(lights.estimate(scene, hit, wo, sampler, i, 0.0f).x) / 4;
      independent += double(estimate_direct(scene, hit, wo, sampler, 0.0f).x) / 4;
    }
    spread_stratified = std::max(spread_stratified, std::abs(stratified - exact));
    spread_independent = std::max(spread_independent, std::abs(independent - exact));
    mean_independent += independent / kTrials;
  }
  CHECK(spread_stratified < 1e-5 * exact);
  CHECK(spread_independent > 0.1 * exact);  // the test's premise: independent choices vary
  CHECK(mean_independent == Approx(exact).epsilon(0.05));
}

TEST_CASE("direct: stratified samples of an area light average to the independent samples' mean", "[trace][direct]") {
  // A 2 x 2 emitter 1 unit above a floor point: the stratified estimate is unbiased and its
  // spread is smaller than independent samples'.
  const std::string scene_text = test::floor_under_square_light(1, 0.5);
  LoadedScene loaded = parse_scene(scene_text, "test.json", ".");
  const Scene& scene = *loaded.scene;
  SurfaceHit hit;
  REQUIRE(scene.intersect(Ray{Vec3(0, 0.5, 0), Vec3(0, -1, 0)}, hit));
  const Vec3 wo(0, 1, 0);
  // Irradiance from a unit-radiance square of half-side a at height h, centred above the
  // point: E = 4 * (a / sqrt(a^2 + h^2)) * atan(a / sqrt(a^2 + h^2)) (two edges' form
  // factors per quadrant, a standard result); L = rho / pi * E.
  const double a = 1, h = 1, s = std::sqrt(a * a + h * h);
  const double exact = 0.5 / kPi * 4.0 * (a / s) * std::atan(a / s);
  constexpr int kTrials = 4000, kN = 16;
  double mean_s = 0, mean_i = 0, var_s = 0, var_i = 0;
  for (int t = 0; t < kTrials; ++t) {
    Sampler sampler(hash_seed(uint64_t(t), 77));  // (hashed: PCG's nearby seeds correlate)
    const StratifiedDirect lights(sampler, kN);
    double st = 0, in = 0;
    for (int i = 0; i < kN; ++i) {
      st += double(lights.estimate(scene, hit, wo, sampler, i, 0.0f).x) / kN;
      in += double(estimate_direct(scene, hit, wo, sampler, 0.0f).x) / kN;
    }
    mean_s += st / kTrials, mean_i += in / kTrials;
    var_s += (st - exact) * (st - exact) / kTrials, var_i += (in - exact) * (in - exact) / kTrials;
  }
  INFO("exact " << exact << " stratified " << mean_s << " independent " << mean_i);
  CHECK(mean_s == Approx(exact).epsilon(0.003));
  CHECK(mean_i == Approx(exact).epsilon(0.01));
  CHECK(var_s < 0.6 * var_i);  // (measured 0.47: the quad's two triangles split the strata)
}
