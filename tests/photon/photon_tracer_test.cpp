// The photon pass: flux bookkeeping against analytic answers, map contents, determinism.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cstring>
#include <tbb/global_control.h>
#include "io/scene_loader.h"
#include "photon/photon_tracer.h"

using namespace caustica;

namespace {
// A point light of intensity I at the centre of a closed box: every photon's first hit is diffuse.
const char* kClosedBox = R"({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1]},
  "materials": {"grey": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
  "objects": [
    {"type": "quad", "origin": [-1, -1, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "grey"},
    {"type": "quad", "origin": [-1, 1, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "grey"},
    {"type": "quad", "origin": [-1, -1, -1], "edge1": [0, 2, 0], "edge2": [0, 0, 2], "material": "grey"},
    {"type": "quad", "origin": [1, -1, -1], "edge1": [0, 2, 0], "edge2": [0, 0, 2], "material": "grey"},
    {"type": "quad", "origin": [-1, -1, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "grey"},
    {"type": "quad", "origin": [-1, -1, 1], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "grey"}
  ],
  "lights": [{"type": "point", "position": [0.1, 0.2, -0.1], "intensity": [1, 2, 3]}]
})";

// A point light at height h over a square floor of half-width a: the floor subtends the
// solid angle 4 asin(a^2 / (a^2 + h^2)), so that fraction / (4 pi) of the photons hit it.
const char* kFloor = R"({
  "camera": {"position": [0, 5, 5], "look_at": [0, 0, 0]},
  "materials": {"white": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}},
  "objects": [{"type": "quad", "origin": [-2, 0, -2], "edge1": [0, 0, 4], "edge2": [4, 0, 0], "material": "white"}],
  "lights": [{"type": "point", "position": [0, 1, 0], "intensity": [10, 10, 10]}]
})";

Color first_bounce_flux(const std::vector<Photon>& photons, float scale, size_t* count = nullptr) {
  glm::dvec3 sum(0.0);
  size_t n = 0;
  for (const Photon& p : photons) {
    if (p.bounces == 0) {
      sum += glm::dvec3(p.power() * scale);
      ++n;
    }
  }
  if (count) *count = n;
  return Color(sum);
}
}  // namespace

TEST_CASE("photon pass: first-bounce flux equals the light's power in a closed box", "[photon][flux]" TIER_UNIT) {
  LoadedScene s = parse_scene(kClosedBox, "box.json", ".");
  PhotonPassSettings settings;
  settings.global_photons = 50000;
  settings.caustic_photons = 0;
  const PhotonPassResult r = trace_photons(*s.scene, settings);
  size_t n_first = 0;
  const Color flux = first_bounce_flux(r.global, r.global_scale, &n_first);
  CHECK(n_first == r.global_emitted);  // nothing escapes a closed box
  const Color power = s.scene->lights[0]->power();
  for (int c = 0; c < 3; ++c) CHECK(flux[c] == Approx(power[c]).epsilon(0.01));
  CHECK(r.global.size() >= settings.global_photons);
  CHECK(r.caustic.empty());
  // Russian roulette by albedo 0.5: on average one photon in two survives each bounce, so
  // the map holds about 1 / (1 - 0.5) = 2 stored photons per emitted one.
  CHECK(double(r.global.size()) / double(r.global_emitted) == Approx(2.0).epsilon(0.03));
}

TEST_CASE("photon pass: first-bounce flux is power times the fraction hitting a diffuse surface", "[photon][flux]" TIER_UNIT) {
  LoadedScene s = parse_scene(kFloor, "floor.json", ".");
  PhotonPassSettings settings;
  settings.global_photons = 60000;
  settings.caustic_photons = 0;
  const PhotonPassResult r = trace_photons(*s.scene, settings);
  size_t n_first = 0;
  const Color flux = first_bounce_flux(r.global, r.global_scale, &n_first);
  const double fraction_hit = double(n_first) / double(r.global_emitted);
  const double a = 2, h = 1;
  const double analytic_fraction = 4.0 * std::asin(a * a / (a * a + h * h)) / (4.0 * kPi);
  CHECK(fraction_hit == Approx(analytic_fraction).epsilon(0.02));
  const Color power = s.scene->lights[0]->power();
  for (int c = 0; c < 3; ++c) CHECK(flux[c] == Approx(power[c] * fraction_hit).epsilon(0.01));
  // An open scene: photons escape, the pass still ends with the wanted count.
  CHECK(r.global.size() >= settings.global_photons);
}

TEST_CASE("photon pass: a scene that stores nothing ends with a warning", "[photon]" TIER_UNIT) {
  // The light faces away from the only surface: every photon escapes.
  const char* text = R"({
    "camera": {"position": [0, 5, 5], "look_at": [0, 0, 0]},
    "materials": {"white": {"type": "diffuse", "albedo": 0.8}, "lamp": {"type": "diffuse", "albedo": 0, "emission": 1}},
    "objects": [{"type": "quad", "origin": [-2, 0, -2], "edge1": [0, 0, 4], "edge2": [4, 0, 0], "material": "white"},
                {"type": "quad", "origin": [0, 1, 0], "edge1": [0, 0, 0.1], "edge2": [0.1, 0, 0], "material": "lamp"}]
  })";
  LoadedScene s = parse_scene(text, "away.json", ".");
  PhotonPassSettings settings;
  settings.global_photons = 10;
  settings.caustic_photons = 10;
  const PhotonPassResult r = trace_photons(*s.scene, settings);
  CHECK(r.global.empty());
  CHECK(r.global_emitted > 1000000);  // reached the cap
  REQUIRE(!r.warnings.empty());
  CHECK_THAT(r.warnings[0], Catch::Contains("global photon map: only 0 of 10"));
}

TEST_CASE("photon pass: caustic map holds only L S+ D photons aimed at the glass", "[photon][caustic]" TIER_UNIT) {
  const char* text = R"({
    "camera": {"position": [0, 5, 5], "look_at": [0, 0, 0]},
    "materials": {"white": {"type": "diffuse", "albedo": 0.8}, "glass": {"type": "glass", "ior": 1.5}},
    "objects": [{"type": "quad", "origin": [-5, 0, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0], "material": "white"},
                {"type": "sphere", "center": [0, 0.8, 0], "radius": 0.5, "material": "glass"}],
    "lights": [{"type": "point", "position": [0, 4, 0], "intensity": [10, 10, 10]}]
  })";
  LoadedScene s = parse_scene(text, "caustic.json", ".");
  PhotonPassSettings settings;
  settings.global_photons = 20000;
  settings.caustic_photons = 20000;
  const PhotonPassResult r = trace_photons(*s.scene, settings);
  REQUIRE(r.caustic.size() >= 20000);
  size_t under_sphere = 0;
  for (const Photon& p : r.caustic) under_sphere += glm::length(Vec2(p.position.x, p.position.z)) < 0.25f;
  // A ball lens of radius 0.5 focuses 0.75 below its centre, near the floor: most photons
  // land within half the ball's radius (the rest were reflected off its surface).
  CHECK(under_sphere > r.caustic.size() * 7 / 10);
  // Aimed emission: almost every emitted photon reaches the sphere; with the light 3.2 above
  // a sphere of radius 0.5 an unaimed one would in only (1 - cos(asin(0.5 / 3.2))) / 2 = 0.6 % of cases.
  CHECK(double(r.caustic.size()) / double(r.caustic_emitted) > 0.5);
  // The caustic flux equals the power sent into the sphere's cone, less Fresnel losses:
  // between 80 % and 100 % of I * solid angle.
  const double cone = 2 * kPi * (1 - std::sqrt(1 - 0.25 / (3.2 * 3.2)));
  double total = 0;
  for (const Photon& p : r.caustic) total += (p.power() * r.caustic_scale).x;
  CHECK(total > 0.8 * 10 * cone);
  CHECK(total < 1.0 * 10 * cone);
}

TEST_CASE("photon pass: the same maps for 1 and 2 threads", "[photon][determinism]" TIER_UNIT) {
  LoadedScene s = parse_scene(kClosedBox, "box.json", ".");
  PhotonPassSettings settings;
  settings.global_photons = 30000;
  PhotonPassResult one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = trace_photons(*s.scene, settings);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = trace_photons(*s.scene, settings);
  }
  REQUIRE(one.global.size() == two.global.size());
  CHECK(one.global_emitted == two.global_emitted);
  CHECK(std::memcmp(one.global.data(), two.global.data(), one.global.size() * sizeof(Photon)) == 0);
}

TEST_CASE("photon pass: caustic photons pass through plastic's coat and land on the floor", "[photon][caustic]" TIER_UNIT) {
  // A smooth plastic ball (a diffuse base under a clear coat) over a floor, a point light above.
  // Light -> coat -> floor is L S D: those photons belong in the caustic map, carrying the
  // coat's Fresnel reflectance; the photons' first hits on the ball itself are not caustics.
  const char* text = R"({
    "camera": {"position": [0, 5, 5], "look_at": [0, 0, 0]},
    "materials": {"white": {"type": "diffuse", "reflectance": 0.8},
                  "plastic": {"type": "plastic", "diffuse_reflectance": 0.3, "int_ior": 1.5}},
    "objects": [{"type": "quad", "origin": [-20, 0, -20], "edge1": [0, 0, 40], "edge2": [40, 0, 0], "material": "white"},
                {"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "plastic"}],
    "lights": [{"type": "point", "position": [0, 3, 0], "intensity": [10, 10, 10]}]
  })";
  LoadedScene s = parse_scene(text, "plastic.json", ".");
  PhotonPassSettings settings;
  settings.global_photons = 1000;
  settings.caustic_photons = 20000;
  const PhotonPassResult r = trace_photons(*s.scene, settings);
  REQUIRE(r.caustic.size() >= 20000);
  size_t on_floor = 0;
  double total = 0;
  for (const Photon& p : r.caustic) {
    on_floor += std::abs(p.position.y) < 1e-3f;
    total += (p.power() * r.caustic_scale).x;
  }
  CHECK(on_floor == r.caustic.size());
  // The coat reflects F (4 % at normal incidence, more at grazing) of the power in the ball's
  // cone: between 4 % and 30 % of I * solid angle reaches the floor.
  const double cone = 2 * kPi * (1 - std::sqrt(1 - 0.25 / (2.0 * 2.0)));
  CHECK(total > 0.04 * 10 * cone * 0.5);
  CHECK(total < 0.3 * 10 * cone);
}

TEST_CASE("photon pass: in a small medium the emission goes on for volume photons alone, the global map unchanged "
          "and the volume photons' total flux the same as without it",
          "[photon][media]" TIER_UNIT) {
  // A fog ball of radius 0.25 in the closed box: a few per cent of the photons scatter in it.
  std::string text = kClosedBox;
  text.replace(text.find(R"("objects": [)"), std::strlen(R"("objects": [)"),
               R"("media": {"fog": {"type": "homogeneous", "sigma_t": 4, "albedo": [0.9, 0.7, 0.5]}},
                  "objects": [{"type": "sphere", "center": [0.3, -0.4, 0.2], "radius": 0.25, "material": "boundary", "interior": "fog"},)");
  text.replace(text.find(R"("materials": {)"), std::strlen(R"("materials": {)"),
               R"("materials": {"boundary": {"type": "null"},)");
  LoadedScene loaded = parse_scene(text, "fog-box.json", ".");
  const Scene& scene = *loaded.scene;
  REQUIRE(scene.has_media());
  PhotonPassSettings s;
  s.global_photons = 4000;
  s.caustic_photons = 0;
  // Each pass's total volume flux (power times scale): with the continuation and without.
  auto total = [](const PhotonPassResult& r) {
    glm::dvec3 sum(0.0);
    for (const Photon& p : r.volume) sum += glm::dvec3(p.power()) * double(r.volume_scale);
    return sum;
  };
  glm::dvec3 with(0.0), without(0.0), with2(0.0), without2(0.0);
  constexpr int kSeeds = 24;
  size_t volume_with = 0, volume_without = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    s.seed = uint64_t(seed) + 100;
    s.volume_min_divisor = 4;
    const PhotonPassResult a = trace_photons(scene, s);
    s.volume_min_divisor = 0;
    const PhotonPassResult b = trace_photons(scene, s);
    // The global map is the same photons from the same emission.
    REQUIRE(a.global.size() >= 4000);  // (the photon that completes the count keeps all its bounces)
    REQUIRE(a.global.size() == b.global.size());
    REQUIRE(a.global_emitted == b.global_emitted);
    REQUIRE(a.global_scale == b.global_scale);
    REQUIRE(std::memcmp(a.global.data(), b.global.data(), a.global.size() * sizeof(Photon)) == 0);
    volume_with += a.volume.size();
    volume_without += b.volume.size();
    const glm::dvec3 ta = total(a), tb = total(b);
    with += ta, with2 += ta * ta, without += tb, without2 += tb * tb;
  }
  INFO("volume photons a pass: " << volume_with / kSeeds << " with, " << volume_without / kSeeds << " without");
  // Without, a few per cent of the global count; with, up to a quarter of it: here the bound
  // on the emission (kVolumeEmission times the global map's) ends it first.
  CHECK(volume_without < 4000 / 8 * kSeeds);
  CHECK(double(volume_with) > 0.9 * double(PhotonPassSettings::kVolumeEmission) * double(volume_without));
  // The totals agree within four standard errors of their difference.
  for (int c = 0; c < 3; ++c) {
    const double n = kSeeds;
    const double ma = with[c] / n, mb = without[c] / n;
    const double va = (with2[c] / n - ma * ma) / (n - 1), vb = (without2[c] / n - mb * mb) / (n - 1);
    INFO("channel " << c << ": " << ma << " with, " << mb << " without");
    CHECK(ma > 0.0);
    CHECK(std::abs(ma - mb) < 4.0 * std::sqrt(va + vb));
    // (and the continuation's spread is the smaller: it averages more photons)
    CHECK(va < vb);
  }
}
