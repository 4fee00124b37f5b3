// The light samplers: the light-bounds tree against brute force (its probabilities add to one
// and match what it samples; it never rules out a light that reaches a point), the cone union,
// and the direct-light estimate it feeds, unbiased and less noisy where lights differ in reach.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <map>
#include "core/light_sampler.h"
#include "core/lights/area.h"
#include "core/lights/point.h"
#include "core/lights/spot.h"
#include "io/scene_loader.h"
#include "support/random.h"
#include "support/render_util.h"
#include "support/scenes.h"
#include "trace/direct.h"

using namespace caustica;
using test::next2;
using test::random_in_box;

namespace {
Vec3 random_direction(Rng& rng) { return sample_uniform_sphere(next2(rng)); }

// A random quad light (two triangles) of side up to 1 at a random place and orientation.
std::unique_ptr<Light> random_quad(Rng& rng, float radiance) {
  const Vec3 o = random_in_box(rng, -4, 4);
  const Frame f(random_direction(rng));
  const float a = 0.1f + rng.next_float(), b = 0.1f + rng.next_float();
  const Vec3 p1 = o + a * f.s, p2 = o + a * f.s + b * f.t, p3 = o + b * f.t;
  std::vector<Primitive> shapes{Primitive::triangle(o, p1, p2), Primitive::triangle(o, p2, p3)};
  return std::make_unique<AreaLight>(std::move(shapes), ColorParam(Color(radiance)));
}

// A mix of point lights, spots, quads and a sphere light of powers over three decades.
std::vector<std::unique_ptr<Light>> random_lights(Rng& rng, int n) {
  std::vector<std::unique_ptr<Light>> lights;
  for (int i = 0; i < n; ++i) {
    const float power = std::pow(10.0f, 3.0f * rng.next_float());
    switch (i % 4) {
      case 0: lights.push_back(std::make_unique<PointLight>(random_in_box(rng, -4, 4), Color(power))); break;
      case 1:
        lights.push_back(std::make_unique<PointLight>(
            random_in_box(rng, -4, 4), Color(power),
            std::make_shared<SpotProfile>(random_direction(rng), 10.0f + 50.0f * rng.next_float(), 5.0f)));
        break;
      case 2: lights.push_back(random_quad(rng, power)); break;
      default: {
        std::vector<Primitive> shapes{Primitive::sphere(random_in_box(rng, -4, 4), 0.1f + 0.3f * rng.next_float())};
        lights.push_back(std::make_unique<AreaLight>(std::move(shapes), ColorParam(Color(power))));
      }
    }
  }
  return lights;
}

// Whether the light sends anything to p (normal n) by a brute-force search over its samples.
bool reaches(const Light& light, const Vec3& p, const Vec3& n, Rng& rng) {
  for (int k = 0; k < 256; ++k) {
    LightSample s;
    if (!light.sample_li(p, next2(rng), s)) continue;
    if (!is_black(s.weight) && std::abs(glm::dot(s.wi, n)) > 1e-4f) return true;
  }
  return false;
}
}  // namespace

TEST_CASE("direction cones: the union holds both cones", "[core][light_sampler]" TIER_UNIT) {
  Rng rng(11);
  for (int t = 0; t < 2000; ++t) {
    const DirectionCone a{random_direction(rng), std::cos(kPi * rng.next_float())};
    const DirectionCone b{random_direction(rng), t % 3 == 0 ? 1.0f : std::cos(kPi * rng.next_float())};
    const DirectionCone u = DirectionCone::unite(a, b);
    const float theta_u = std::acos(std::clamp(u.cos_theta, -1.0f, 1.0f));
    // Each cone's axis turned to its edge, all the way round, lies within the union.
    for (const DirectionCone& c : {a, b}) {
      const float theta = std::acos(std::clamp(c.cos_theta, -1.0f, 1.0f));
      const Frame f(c.axis);
      for (int k = 0; k < 16; ++k) {
        const float phi = 2.0f * kPi * float(k) / 16.0f;
        const Vec3 edge = f.to_world(Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
        const float angle = std::acos(std::clamp(glm::dot(edge, u.axis), -1.0f, 1.0f));
        CHECK(angle <= theta_u + 1e-3f);
      }
    }
    // and it is no wider than both cones' hull needs: at most the sum of the half-angles and
    // the axes' angle, halved (or pi).
    const float theta_a = std::acos(std::clamp(a.cos_theta, -1.0f, 1.0f)), theta_b = std::acos(std::clamp(b.cos_theta, -1.0f, 1.0f));
    const float theta_d = std::acos(std::clamp(glm::dot(a.axis, b.axis), -1.0f, 1.0f));
    CHECK(theta_u <= std::max({theta_a, theta_b, 0.5f * (theta_a + theta_b + theta_d)}) + 1e-3f);
  }
}

TEST_CASE("light tree: probabilities add to one, match what it samples, and never rule out a light that reaches the point",
          "[core][light_sampler]" TIER_UNIT) {
  Rng rng(5);
  int reached = 0;
  for (int n : {1, 2, 7, 40}) {
    const std::vector<std::unique_ptr<Light>> lights = random_lights(rng, n);
    const LightSampler tree(lights, LightSamplerKind::Tree);
    CHECK(tree.nodes() == size_t(2 * n - 1));
    for (int t = 0; t < 40; ++t) {
      const Vec3 p = random_in_box(rng, -5, 5);
      const Vec3 normal = t % 5 == 0 ? Vec3(0.0f) : random_direction(rng);
      double sum = 0;
      bool any = false;
      for (size_t i = 0; i < lights.size(); ++i) {
        const float pmf = tree.pmf(p, normal, i);
        sum += double(pmf);
        // A light that lights p has a non-zero probability (the bounds are conservative).
        if (reaches(*lights[i], p, normal == Vec3(0.0f) ? random_direction(rng) : normal, rng)) {
          any = true;
          CHECK(pmf > 0.0f);
        }
      }
      // What is missing to one is the chance that the descent ends where both children's bounds
      // rule the point out (a sample with no light, never a light that reaches p).
      CHECK(sum <= 1.0 + 1e-4);
      // Sampled frequencies against pmf, and the pmf sample() reports is pmf()'s.
      std::map<int, int> counts;
      constexpr int kDraws = 4000;
      int misses = 0;
      for (int k = 0; k < kDraws; ++k) {
        float pmf = 0;
        const int i = tree.sample(p, normal, rng.next_float(), pmf);
        if (i < 0) {
          ++misses;
          continue;
        }
        ++counts[i];
        CHECK(pmf == Approx(tree.pmf(p, normal, size_t(i))).epsilon(1e-4));
      }
      for (const auto& [i, c] : counts) {
        const double expected = double(tree.pmf(p, normal, size_t(i))) * kDraws;
        CHECK(std::abs(double(c) - expected) <= 5.0 * std::sqrt(expected + 1.0) + 1.0);
      }
      const double expected_misses = (1.0 - sum) * kDraws;
      CHECK(std::abs(double(misses) - expected_misses) <= 5.0 * std::sqrt(std::max(expected_misses, 0.0) + 1.0) + 1.0);
      if (any) ++reached;
    }
  }
  CHECK(reached > 100);  // the test's premise: most points see some light
}

TEST_CASE("light tree: the dim light beside a point gets its samples (Mitsuba's hello.xml)", "[core][light_sampler]" TIER_UNIT) {
  // Two point lights of intensity 10 and 1, a floor point under the dim one and far from the
  // bright one: by power the dim light gets 1/11 of the shadow rays; the tree gives it most.
  const std::string text = test::floor_scene(R"({"type": "point", "position": [20, 4, 0], "intensity": 10},
                                                 {"type": "point", "position": [0, 1, 0], "intensity": 1})");
  LoadedScene loaded = parse_scene(text, "test.json", ".");
  const Scene& scene = *loaded.scene;
  const Vec3 p(0.0f), n(0, 1, 0);
  CHECK(scene.photon_light_pmf(1) == Approx(1.0 / 11.0));
  CHECK(scene.light_pmf(p, n, 1) > 0.9f);
  CHECK(scene.light_pmf(p, n, 0) + scene.light_pmf(p, n, 1) == Approx(1.0));
  // With the power sampler the scene chooses as before.
  loaded.scene->render.light_sampler = LightSamplerKind::Power;
  loaded.scene->build(loaded.scene->accel().primitives());
  CHECK(scene.light_pmf(p, n, 1) == Approx(1.0 / 11.0));
}

TEST_CASE("light tree: the direct light it estimates is unbiased, with less spread than choosing by power",
          "[core][light_sampler][direct]" TIER_UNIT) {
  // Eight point lights of powers over two decades around a floor point, some far: the exact
  // direct light is their sum, rho / pi * I cos / d^2.
  std::string lights;
  std::vector<std::pair<Vec3, float>> list;
  Rng rng(3);
  for (int i = 0; i < 8; ++i) {
    const Vec3 at(8.0f * rng.next_float() - 4.0f, 0.2f + 3.0f * rng.next_float(), 8.0f * rng.next_float() - 4.0f);
    const float intensity = std::pow(10.0f, 2.0f * rng.next_float());
    list.emplace_back(at, intensity);
    lights += std::string(i ? "," : "") + R"({"type": "point", "position": [)" + std::to_string(at.x) + "," +
              std::to_string(at.y) + "," + std::to_string(at.z) + R"(], "intensity": )" + std::to_string(intensity) + "}";
  }
  double exact = 0;
  for (const auto& [at, intensity] : list) {
    const double d2 = double(glm::dot(at, at));
    exact += 0.5 / kPi * double(intensity) * double(at.y) / std::sqrt(d2) / d2;
  }
  double spread[2] = {0, 0};
  for (const LightSamplerKind kind : {LightSamplerKind::Tree, LightSamplerKind::Power}) {
    LoadedScene loaded = parse_scene(test::floor_scene(lights), "test.json", ".");
    loaded.scene->render.light_sampler = kind;
    loaded.scene->build(loaded.scene->accel().primitives());
    const Scene& scene = *loaded.scene;
    SurfaceHit hit;
    REQUIRE(scene.intersect(Ray{Vec3(0, 4, 0), Vec3(0, -1, 0)}, hit));
    constexpr int kN = 40000;
    double mean = 0, m2 = 0;
    Sampler sampler(17);
    for (int k = 0; k < kN; ++k) {
      const double v = double(estimate_direct(scene, hit, Vec3(0, 1, 0), sampler, 0.0f).x);
      mean += v / kN;
      m2 += v * v / kN;
    }
    const double sd = std::sqrt(std::max(0.0, m2 - mean * mean));
    CHECK(mean == Approx(exact).epsilon(4.0 * sd / std::sqrt(double(kN)) / exact + 1e-4));
    spread[kind == LightSamplerKind::Tree ? 0 : 1] = sd;
  }
  CHECK(spread[0] < 0.7 * spread[1]);
}

TEST_CASE("light tree: lights at infinity are chosen n / (n + 1) of the time, by power among them",
          "[core][light_sampler]" TIER_UNIT) {
  const std::string text = test::floor_scene(R"({"type": "point", "position": [0, 2, 0], "intensity": 1},
      {"type": "directional", "direction": [0, -1, 0], "irradiance": 1},
      {"type": "directional", "direction": [1, -1, 0], "irradiance": 3})");
  LoadedScene loaded = parse_scene(text, "test.json", ".");
  const Scene& scene = *loaded.scene;
  const Vec3 p(0.3f, 0.0f, 0.1f), n(0, 1, 0);
  CHECK(scene.light_pmf(p, n, 0) == Approx(1.0 / 3.0));
  CHECK(scene.light_pmf(p, n, 1) == Approx(2.0 / 3.0 * 0.25));
  CHECK(scene.light_pmf(p, n, 2) == Approx(2.0 / 3.0 * 0.75));
}

TEST_CASE("light sampler: --light-sampler and the render block's light_sampler; unknown names are errors",
          "[core][light_sampler][scene_loader]" TIER_UNIT) {
  std::string text = test::floor_scene(R"({"type": "point", "position": [0, 2, 0], "intensity": 1})");
  text.insert(text.find('{') + 1, R"("render": {"light_sampler": "power"},)");
  CHECK(parse_scene(text, "test.json", ".").scene->render.light_sampler == LightSamplerKind::Power);
  std::string bad = test::floor_scene(R"({"type": "point", "position": [0, 2, 0], "intensity": 1})");
  bad.insert(bad.find('{') + 1, R"("render": {"light_sampler": "bvh"},)");
  REQUIRE_THROWS_WITH(parse_scene(bad, "test.json", "."),
                      Catch::Contains("test.json: /render/light_sampler: unknown light_sampler \"bvh\" (known: tree, power)"));
}

namespace {
// A floor and a back wall lit by a small bright quad, a wide dim one facing sideways, a sphere
// light and a spot: the light tree weighs them differently at every point.
std::string four_lights_scene(const char* sampler) {
  return std::string(R"({
    "render": {"light_sampler": ")") + sampler + R"(", "max_depth": 4},
    "camera": {"position": [0, 2, -6], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov": 60},
    "materials": {"white": {"type": "diffuse", "reflectance": 0.6},
                  "glossy": {"type": "roughconductor", "material": "Al", "alpha": 0.2},
                  "bright": {"type": "diffuse", "reflectance": 0, "emission": [40, 40, 40]},
                  "dim": {"type": "diffuse", "reflectance": 0, "emission": [0.5, 0.5, 0.5]},
                  "ball": {"type": "diffuse", "reflectance": 0, "emission": [4, 2, 1]}},
    "objects": [{"type": "quad", "origin": [-4, 0, -4], "edge1": [0, 0, 8], "edge2": [8, 0, 0], "material": "white"},
                {"type": "quad", "origin": [-4, 0, 2], "edge1": [8, 0, 0], "edge2": [0, 4, 0], "material": "glossy"},
                {"type": "quad", "origin": [1.5, 3, -0.25], "edge1": [0.5, 0, 0], "edge2": [0, 0, 0.5], "material": "bright"},
                {"type": "quad", "origin": [-3.5, 0.2, -2], "edge1": [0, 0, 3], "edge2": [0, 2, 0], "material": "dim"},
                {"type": "sphere", "center": [0, 0.4, 0], "radius": 0.3, "material": "ball"}],
    "lights": [{"type": "spot", "position": [-1, 3, -1], "target": [-1, 0, 0.5], "intensity": 30, "cutoff_angle": 25}]})";
}
}  // namespace

TEST_CASE("light tree: path and photon images agree with the power sampler's (MIS weights use the tree's probabilities)",
          "[core][light_sampler][trace]" TIER_FIGURE) {
  const auto by_power = test::render_text(four_lights_scene("power"), "path", "{}", 256, 48, 32, 3);
  const auto by_tree = test::render_text(four_lights_scene("tree"), "path", "{}", 256, 48, 32, 4);
  const auto photon = test::render_text(four_lights_scene("tree"), "photon", "{}", 64, 48, 32, 5);
  const glm::dvec3 reference = test::region_mean(by_power.image, 0, 0, 48, 32);
  REQUIRE(reference.x > 0.05);
  CHECK(test::region_mean(by_tree.image, 0, 0, 48, 32).x == Approx(reference.x).epsilon(0.02));
  CHECK(test::region_mean(photon.image, 0, 0, 48, 32).x == Approx(reference.x).epsilon(0.03));
  // Region by region (6 of 8 x 8 pixels): the floor under each light, the wall's reflections.
  for (int y = 0; y < 32; y += 8)
    for (int x = 0; x < 48; x += 8) {
      const double r = test::region_mean(by_power.image, x, y, x + 8, y + 8).x;
      if (r < 0.02) continue;
      CHECK(test::region_mean(by_tree.image, x, y, x + 8, y + 8).x == Approx(r).epsilon(0.06));
    }
}
