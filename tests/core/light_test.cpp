// Spot profiles, environment-map sampling against its density (chi-square) and light-block
// errors.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "support/scenes.h"
#include "core/lights/environment.h"
#include "core/lights/area.h"
#include "core/lights/point.h"
#include "core/lights/spot.h"
#include "io/scene_loader.h"
#include "support/chi2.h"
#include "support/random.h"

using namespace caustica;
using test::floor_scene;
using test::next2;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}  // namespace

TEST_CASE("spot profile: full inside the beam, linear in the angle to the cutoff, zero outside", "[core][light]" TIER_UNIT) {
  const SpotProfile spot(Vec3(0, 0, 1), 30.0f, 10.0f);
  auto at = [](double deg) { return Vec3(float(std::sin(deg * kDeg)), 0.0f, float(std::cos(deg * kDeg))); };
  CHECK(spot.falloff(at(0)) == 1.0f);
  CHECK(spot.falloff(at(9.9)) == 1.0f);
  CHECK(spot.falloff(at(20)) == Approx(0.5).margin(1e-3));
  CHECK(spot.falloff(at(25)) == Approx(0.25).margin(1e-3));
  CHECK(spot.falloff(at(30.1)) == 0.0f);
  CHECK(spot.falloff(Vec3(0, 0, -1)) == 0.0f);
  // A hard-edged spot subtends 2 pi (1 - cos cutoff); the soft one integrates the falloff:
  // 2 pi [1 - cos b + integral_b^c (c - t) / (c - b) sin t dt], closed form below.
  const SpotProfile hard(Vec3(0, 1, 0), 30.0f, 30.0f);
  CHECK(hard.integral().x == Approx(2 * 3.14159265358979 * (1 - std::cos(30 * kDeg))).epsilon(1e-5));
  const double b = 10 * kDeg, c = 30 * kDeg;
  const double integral = (std::cos(b) * 0 + (-(std::sin(c) - std::sin(b)) + (c - b) * std::cos(b))) / (c - b);
  // integral_b^c (c - t) sin t dt = (c - b) cos b - (sin c - sin b)
  CHECK(spot.integral().x == Approx(2 * 3.14159265358979 * (1 - std::cos(b) + integral)).epsilon(1e-4));
}

TEST_CASE("environment map: sampling matches pdf_escaped (chi-square), and the density integrates to 1",
          "[core][light][chi2]" TIER_UNIT) {
  // A gradient with a bright spot, rotated: sampling must follow luminance * sin(theta).
  Image img(32, 16);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) img.at(x, y) = Color(0.1f + 0.05f * float(x), 0.2f, 0.3f + 0.1f * float(y));
  }
  img.at(20, 4) = Color(200.0f);
  const float a = 0.7f;
  const glm::mat3 rot(Vec3(std::cos(a), 0, -std::sin(a)), Vec3(0, 1, 0), Vec3(std::sin(a), 0, std::cos(a)));
  EnvironmentLight env(img, 1.0f, rot);
  env.set_scene_sphere(Vec3(0.0f), 1.0f);
  Rng rng(5);
  test::SphereHistogram hist(32, 64);
  const int n = 400000;
  int bad = 0, at_pole = 0;
  for (int i = 0; i < n; ++i) {
    float pdf = 0;
    const Vec3 d = env.sample_direction(next2(rng), pdf);
    if (!(pdf > 0)) ++at_pole;  // sin(theta) rounds to 0: sample_li refuses these
    else if (std::abs(pdf - env.pdf_escaped(d)) > 1e-3f * pdf) ++bad;
    hist.add(d);
  }
  CHECK(bad == 0);
  CHECK(at_pole <= 10);
  const auto expected = hist.expected([&](const Vec3& w) { return double(env.pdf_escaped(w)); }, n, 32);
  CHECK(test::sum(expected) == Approx(n).epsilon(0.01));
  const test::Chi2Result chi = test::chi2_test(hist.counts(), expected);
  INFO(chi.message);
  CHECK(chi.accepts(1e-3));
  // Negative control: the same samples against a uniform density are rejected.
  const auto uniform = hist.expected([](const Vec3&) { return 1.0 / (4.0 * test::kPi64); }, n, 8);
  CHECK_FALSE(test::chi2_test(hist.counts(), uniform).accepts(1e-3));
}

TEST_CASE("environment map: the bright pixel is seen where to_world puts it", "[core][light]" TIER_UNIT) {
  Image img(8, 4);
  for (Color& c : img.pixels) c = Color(1.0f);
  img.at(0, 1) = Color(50.0f);  // u in [0, 1/8): phi near 0, i.e. local -z; v in [1/4, 1/2)
  EnvironmentLight env(img, 2.0f, glm::mat3(1.0f));
  const float theta = 0.375f * 3.14159265f, phi = 0.0625f * 2 * 3.14159265f;
  const Vec3 local(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
  CHECK(env.escaped(local).x == Approx(100.0f));  // scale 2
  CHECK(env.escaped(Vec3(0, 1, 0)).x == Approx(2.0f));
}

TEST_CASE("lights: bad light blocks are errors naming the key", "[core][light][scene_loader]" TIER_UNIT) {
  auto load = [](const std::string& light) { return parse_scene(floor_scene(light), "l.json", "."); };
  CHECK_THROWS_WITH(load(R"({"type": "spot", "position": [0, 1, 0], "intensity": 1})"),
                    Catch::Contains("give either direction or target"));
  CHECK_THROWS_WITH(load(R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "intensity": 1, "cutoff_angle": 10, "beam_width": 20})"),
                    Catch::Contains("/lights/0/beam_width"));
  CHECK_THROWS_WITH(load(R"({"type": "directional", "direction": [0, 0, 0], "irradiance": 1})"),
                    Catch::Contains("/lights/0/direction"));
  CHECK_THROWS_WITH(load(R"({"type": "envmap", "filename": "no-such-sky.exr"})"),
                    Catch::Contains("/lights/0/filename") && Catch::Contains("no-such-sky.exr"));
  CHECK_THROWS_WITH(load(R"({"type": "envmap", "filename": "x.hdr", "to_world": [[2, 0, 0], [0, 1, 0], [0, 0, 1]]})"),
                    Catch::Contains("/lights/0/"));
  CHECK_THROWS_WITH(load(R"({"type": "constant", "radiance": 0})"), Catch::Contains("/lights/0/radiance"));
  CHECK_THROWS_WITH(load(R"({"type": "sun"})"), Catch::Contains("unknown light type \"sun\"") && Catch::Contains("envmap"));
}
