// Next-event estimation: stratified light samples.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <set>
#include <vector>
#include "io/scene_loader.h"
#include "trace/direct.h"
#include "support/scenes.h"

using namespace caustica;

TEST_CASE("direct: stratified light samples choose each of n equal lights exactly once", "[trace][direct]" TIER_UNIT) {
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

TEST_CASE("direct: stratified samples of an area light average to the independent samples' mean", "[trace][direct]" TIER_UNIT) {
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

TEST_CASE("direct: single scattering from an area light in fog matches its double integral, for a ray passing the "
          "light and one ending on it",
          "[trace][direct][media]" TIER_UNIT) {
  // Fog everywhere (around the camera, bounded by nothing), a 1 x 1 light at height 1 facing down.
  LoadedScene loaded = parse_scene(R"({"camera": {"position": [0, -3, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "medium": "fog"},
    "media": {"fog": {"type": "homogeneous", "sigma_t": 0.5, "albedo": 0.8}},
    "materials": {"light": {"type": "diffuse", "albedo": 0, "emission": [2, 2, 2]}},
    "objects": [{"type": "quad", "origin": [-0.5, 1, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "light"}]})",
                                   "fog-light.json", ".");
  const Scene& scene = *loaded.scene;
  REQUIRE(scene.lights.size() == 1);
  const int32_t medium = scene.camera_medium;
  REQUIRE(medium >= 0);
  const Light& light = *scene.lights[0];
  const Vec3 n = light.sample_origin(Vec2(0.5f)).n;
  const float Le = light.surface_radiance().x;
  const double sigma_t = 0.5, sigma_s = 0.4;
  // The in-scattered light along [0, tmax]: integral of Tr(t) sigma_s (1 / 4 pi) Le cos_l / d^2
  // Tr(d) over the light's area and t, by the midpoint rule (the light faces down: cos_l from n).
  auto brute = [&](const Ray& ray, double tmax) {
    constexpr int kT = 1500, kA = 120;
    double sum = 0;
    for (int i = 0; i < kT; ++i) {
      const double t = (i + 0.5) * tmax / kT;
      const Vec3 x = ray.at(float(t));
      double s = 0;
      for (int a = 0; a < kA; ++a)
        for (int b = 0; b < kA; ++b) {
          const Vec3 y(-0.5f + (a + 0.5f) / kA, 1.0f, -0.5f + (b + 0.5f) / kA);
          const Vec3 d = x - y;
          const double d2 = glm::dot(d, d), cos_l = glm::dot(glm::normalize(d), n);
          if (cos_l > 0) s += Le * cos_l / d2 * std::exp(-sigma_t * std::sqrt(d2)) / (double(kA) * kA);
        }
      sum += std::exp(-sigma_t * t) * sigma_s / (4.0 * kPi) * s * tmax / kT;
    }
    return sum;
  };
  struct Case {
    Ray ray;
    float tmax;
  };
  // Passing under the light at height 0.6 (to 30, where the fog has taken all); rising into its
  // middle from 2 below (ending on it: the shading points come arbitrarily close to the light).
  const Case cases[] = {{Ray{Vec3(-3.0f, 0.6f, 0.1f), Vec3(1.0f, 0.0f, 0.0f), kInfinity}, 30.0f},
                        {Ray{Vec3(0.1f, -1.0f, 0.2f), Vec3(0.0f, 1.0f, 0.0f), kInfinity}, 2.0f}};
  for (const Case& c : cases) {
    const double expected = brute(c.ray, c.tmax);
    // The ray ending on the light also as the eye path gives it: that light named as the
    // segment's end (a light sample and a phase sample under MIS at t).
    std::vector<const Light*> ends{nullptr};
    if (c.tmax < 10.0f) ends.push_back(&light);
    for (const Light* end : ends) {
      Sampler sampler(61);
      constexpr int kN = 400000;
      double sum = 0, sum2 = 0;
      for (int i = 0; i < kN; ++i) {
        const double v = single_scattering(scene, c.ray, c.tmax, medium, Color(0.5f), Color(0.4f), sampler, end).x;
        sum += v, sum2 += v * v;
      }
      const double mean = sum / kN, se = std::sqrt((sum2 / kN - mean * mean) / kN);
      INFO("tmax " << c.tmax << (end ? ", ending on the light" : "") << ": expected " << expected << ", mean " << mean
                   << " +- " << se);
      CHECK(expected > 0.005);
      CHECK(mean == Approx(expected).epsilon(0.02));
      // A spread that lets 400k samples say so.
      CHECK(se < 0.005 * expected);
    }
  }
}
