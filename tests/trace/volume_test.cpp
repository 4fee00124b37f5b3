// Path tracing through participating media against analytic results: a furnace filled with a
// scattering medium, transmittance through an absorbing slab for camera and shadow rays, and
// the readers' and integrators' refusals.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "io/scene_loader.h"
#include "io/volume_io.h"
#include "support/grids.h"
#include "support/errors.h"
#include "support/render_util.h"
#include "support/run.h"
#include "support/temp_dir.h"
#include "trace/integrator.h"

using namespace caustica;
using test::region_mean;
using test::render_text;

namespace {
// The camera at the centre of a closed black shell of radiance 1 (normals flipped inward) in a
// medium of albedo 1: the radiance is 1 everywhere, whatever the medium scatters (white
// furnace). `fog` is the medium block; `inner` adds a null sphere of radius 1.2 holding the
// medium, vacuum outside it; without it the camera's medium fills the shell.
std::string furnace_in_medium(const std::string& fog, bool inner) {
  std::string objects =
      R"({"type": "sphere", "center": [0.1, -0.2, 0.1], "radius": 2, "material": "shell", "flip_normal": true})";
  if (inner) objects += R"(, {"type": "sphere", "center": [0, 0, 0], "radius": 1.2, "material": "boundary", "interior": "fog"})";
  return R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0], "fov": 90, "medium": "fog"},
    "render": {"max_depth": 1000},
    "media": {"fog": )" + fog + R"(},
    "materials": {"shell": {"type": "diffuse", "albedo": 0, "emission": [1, 1, 1]}, "boundary": {"type": "null"}},
    "objects": [)" + objects + "]}";
}

// An absorbing slab (null boundaries at z = 1 and z = 3, normals outward) between the camera
// and an emitter of radiance 1: the pixels read exp(-2 sigma_t).
const char* kSlab = R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0], "fov": 2},
  "media": {"ink": {"type": "homogeneous", "sigma_t": [0.2, 0.5, 1.0], "albedo": 0}},
  "materials": {"light": {"type": "diffuse", "albedo": 0, "emission": [1, 1, 1]}, "boundary": {"type": "null"}},
  "objects": [{"type": "quad", "origin": [-5, -5, 1], "edge1": [0, 10, 0], "edge2": [10, 0, 0], "material": "boundary", "interior": "ink"},
              {"type": "quad", "origin": [-5, -5, 3], "edge1": [10, 0, 0], "edge2": [0, 10, 0], "material": "boundary", "interior": "ink"},
              {"type": "quad", "origin": [-5, -5, 5], "edge1": [0, 10, 0], "edge2": [10, 0, 0], "material": "light"}]})";

// A diffuse floor lit by a point light 4 above it through an absorbing slab from y = 3.2 to 3.8
// (only the shadow rays cross it), seen from straight above at height 3.
const char* kShadowSlab = R"({"camera": {"position": [0, 3, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 2},
  "media": {"ink": {"type": "homogeneous", "sigma_a": [0.5, 1.0, 2.0], "sigma_s": 0}},
  "materials": {"floor": {"type": "diffuse", "reflectance": 0.5}, "boundary": {"type": "null"}},
  "objects": [{"type": "quad", "origin": [-50, 0, -50], "edge1": [0, 0, 100], "edge2": [100, 0, 0], "material": "floor"},
              {"type": "quad", "origin": [-50, 3.2, -50], "edge1": [100, 0, 0], "edge2": [0, 0, 100], "material": "boundary", "interior": "ink"},
              {"type": "quad", "origin": [-50, 3.8, -50], "edge1": [0, 0, 100], "edge2": [100, 0, 0], "material": "boundary", "interior": "ink"}],
  "lights": [{"type": "point", "position": [0, 4, 0], "intensity": [1, 1, 1]}]})";
}  // namespace

TEST_CASE("path through media: a white furnace filled with a scattering medium reads the shell's radiance",
          "[trace][media][furnace]" TIER_UNIT) {
  // Chromatic extinction and forward scattering; the medium filling the shell, and held by a
  // null sphere inside it.
  for (const bool inner : {false, true}) {
    for (const char* fog : {R"({"type": "homogeneous", "sigma_t": [0.4, 1.0, 2.5], "albedo": 1, "phase": {"type": "hg", "g": 0.6}})",
                            R"({"type": "homogeneous", "sigma_a": 0, "sigma_s": 1.5})"}) {
      INFO((inner ? "inside a null sphere: " : "filling the shell: ") << fog);
      const auto r = render_text(furnace_in_medium(fog, inner), "path", "{}", 16, 24, 24);
      const Color mean = r.image.mean();
      for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(1.0).epsilon(0.015));
      for (int gy = 0; gy < 2; ++gy)
        for (int gx = 0; gx < 2; ++gx) {
          const glm::dvec3 m = region_mean(r.image, gx * 12, gy * 12, gx * 12 + 12, gy * 12 + 12);
          CHECK((m.x + m.y + m.z) / 3.0 == Approx(1.0).epsilon(0.03));
        }
      CHECK(r.stats.bad_samples == 0);
    }
  }
}

TEST_CASE("path through media: camera rays through an absorbing slab read exp(-sigma_t d)", "[trace][media]" TIER_UNIT) {
  // (A medium that scatters nothing is passed with its transmittance: no noise.)
  const Color mean = render_text(kSlab, "path", "{}", 4, 8, 8).image.mean();
  const double sigma[3] = {0.2, 0.5, 1.0};
  for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(std::exp(-2.0 * sigma[c])).epsilon(0.001));
}

TEST_CASE("media: shadow rays through an absorbing slab take its transmittance", "[trace][media]" TIER_UNIT) {
  // L = albedo / pi * I / d^2 * exp(-sigma_a * 0.6), the light 4 above the floor's centre. (Every
  // integrator that takes direct light by shadow rays: photon-direct takes it from its map.)
  const double sigma[3] = {0.5, 1.0, 2.0};
  for (const char* integrator : {"path", "photon", "sppm", "whitted"}) {
    INFO(integrator);
    const Color mean = render_text(kShadowSlab, integrator, "{}", 4, 8, 8).image.mean();
    for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(0.5 / double(kPi) / 16.0 * std::exp(-0.6 * sigma[c])).epsilon(0.01));
  }
}

TEST_CASE("media: bad media blocks and references are errors naming the place", "[io][media]" TIER_UNIT) {
  auto error = [](const std::string& medium, const std::string& object_keys = R"(, "interior": "fog")") {
    const std::string scene = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]}, "media": {"fog": )" + medium +
                              R"(}, "materials": {"m": {"type": "null"}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m")" + object_keys + "}]}";
    return test::error_of([&] { parse_scene(scene, "s.json", "."); });
  };
  CHECK(error(R"({"type": "homogeneous", "sigma_t": 1})").empty());
  CHECK_THAT(error(R"({"type": "homogeneous", "sigma_t": -1})"), Catch::Contains("s.json") && Catch::Contains("/media/fog/sigma_t"));
  CHECK_THAT(error(R"({"type": "homogeneous", "albedo": [0.5, 1.5, 0.5]})"),
             Catch::Contains("/media/fog/albedo") && Catch::Contains("[0, 1]"));
  CHECK_THAT(error(R"({"type": "homogeneous", "sigma_t": 1, "sigma_s": 1})"), Catch::Contains("not both"));
  CHECK_THAT(error(R"({"type": "homogeneous", "phase": {"type": "hg", "g": 1}})"),
             Catch::Contains("/media/fog/phase/g") && Catch::Contains("(-1, 1)"));
  CHECK_THAT(error(R"({"type": "homogeneous", "phase": {"type": "rayleigh"}})"),
             Catch::Contains("/media/fog/phase/type") && Catch::Contains("isotropic, hg"));
  CHECK_THAT(error(R"({"type": "fog"})"),
             Catch::Contains("/media/fog/type") && Catch::Contains("homogeneous, heterogeneous"));
  CHECK_THAT(error(R"({"type": "homogeneous"})", R"(, "exterior": "smoke")"),
             Catch::Contains("/objects/0/exterior") && Catch::Contains("unknown medium \"smoke\"") && Catch::Contains("fog"));
  CHECK_THAT(error(R"({"type": "homogeneous", "sigma_t": 1, "density": 2})"), Catch::Contains("density"));
}

TEST_CASE("media: every integrator reads camera rays through an absorbing slab as exp(-sigma_t d)", "[trace][media]" TIER_PROCESS) {
  const double sigma[3] = {0.2, 0.5, 1.0};
  for (const IntegratorPlugin& plugin : integrator_plugins()) {
    INFO(plugin.name);
    // (Few photons: from a light in a black world they all escape, and a pass emits 50 times as
    // many as it wants, and a million more, before it gives up.)
    const bool photons = plugin.reads("photons");
    if (photons && test::kSanitized) continue;  // (a million photons a pass: the Release suite's)
    const Color mean = render_text(kSlab, plugin.name, photons ? R"({"photons": 100})" : "{}", 4, 8, 8).image.mean();
    for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(std::exp(-2.0 * sigma[c])).epsilon(0.001));
  }
  // And from the command line: an image written, no refusal.
  test::TempDir dir;
  dir.write("slab.json", kSlab);
  const test::RunResult r = test::run_caustica("render slab.json --integrator sppm --photons 100 --spp 1 -o out.exr -q", dir);
  CHECK(r.exit_code == 0);
  CHECK(std::filesystem::exists(dir.file("out.exr")));
}

TEST_CASE("path through media: a white furnace filled with a grid medium (delta and ratio tracking) reads the "
          "shell's radiance",
          "[trace][media][furnace]" TIER_UNIT) {
  test::TempDir dir;
  Rng rng(9);
  const VolumeGrid g = test::make_grid(6, 5, 4, Vec3(-1.0f), Vec3(1.0f), [&](int, int, int) {
    const float a = rng.next_float();
    return 3.0f * a * rng.next_float();
  });
  dir.write("smoke.vol", format_vol(g));
  const std::string fog =
      R"({"type": "heterogeneous", "sigma_t": {"type": "gridvolume", "filename": "smoke.vol"}, "albedo": 1, "scale": 2,
          "phase": {"type": "hg", "g": -0.3}})";
  const auto r = render_text(furnace_in_medium(fog, false), "path", "{}", 16, 24, 24, 1, 0, dir.path().string());
  const Color mean = r.image.mean();
  for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(1.0).epsilon(0.015));
  CHECK(r.stats.bad_samples == 0);
  // Bad blocks: a negative extinction, a grid file that is not there.
  auto error = [&](const std::string& medium) {
    return test::error_of([&] { parse_scene(furnace_in_medium(medium, false), "s.json", dir.path().string()); });
  };
  CHECK_THAT(error(R"({"type": "heterogeneous", "sigma_t": [1, 2, -3]})"), Catch::Contains("/media/fog/sigma_t"));
  CHECK_THAT(error(R"({"type": "heterogeneous", "sigma_t": {"type": "gridvolume", "filename": "none.vol"}})"),
             Catch::Contains("/media/fog/sigma_t/filename") && Catch::Contains("none.vol"));
  dir.write("short.vol", format_vol(g).substr(0, 100));
  CHECK_THAT(error(R"({"type": "heterogeneous", "sigma_t": {"type": "gridvolume", "filename": "short.vol"}})"),
             Catch::Contains("s.json") && Catch::Contains("/media/fog/sigma_t/filename") && Catch::Contains("short.vol") &&
                 Catch::Contains("truncated"));
}

TEST_CASE("media: identical pixels for 1 and 2 threads (path, sppm, whitted, photon-direct)", "[trace][media][determinism]" TIER_UNIT) {
  const std::string scene =
      furnace_in_medium(R"({"type": "homogeneous", "sigma_t": [0.4, 1.0, 2.5], "albedo": 0.9, "phase": {"type": "hg", "g": 0.5}})", true);
  for (const char* integrator : {"path", "sppm", "whitted", "photon-direct"}) {
    INFO(integrator);
    const std::string settings = std::string(integrator) == "path" || std::string(integrator) == "whitted" ? "{}" : R"({"photons": 5000})";
    const auto one = render_text(scene, integrator, settings, 2, 16, 16, 9, 1);
    const auto two = render_text(scene, integrator, settings, 2, 16, 16, 9, 2);
    CHECK(one.image.mean().x > 0.1f);
    CHECK(one.image.pixels == two.image.pixels);
  }
}

namespace {
// Transmittance (uncollided and scattered) of a plane-parallel slab of optical thickness tau,
// isotropic scattering of this albedo, under a beam at normal incidence: a one-dimensional
// random walk of the direction cosine, independent of the renderer's code.
double slab_transmittance(double tau, double albedo, int walks, uint64_t seed) {
  Rng rng(seed);
  double through = 0.0;
  for (int i = 0; i < walks; ++i) {
    double z = 0.0, mu = 1.0, w = 1.0;  // depth in optical units, cosine to the downward normal
    for (int event = 0; event < 100000; ++event) {
      z += mu * -std::log(1.0 - double(rng.next_float()) * 0.99999999);
      if (z >= tau) {
        through += w;
        break;
      }
      if (z < 0.0) break;
      w *= albedo;
      mu = 2.0 * double(rng.next_float()) - 1.0;
    }
  }
  return through / walks;
}
}  // namespace

TEST_CASE("path through media: a scattering slab transmits what a one-dimensional random walk gives",
          "[trace][media][slab]" TIER_UNIT) {
  // A slab 1 thick (sigma_t 1) between null boundaries at y = 1 and 2, under a directional light
  // of irradiance 1 straight down; the camera between the slab and a floor of albedo 0.001 (its
  // light sent back up and returned is 1e-3 of the total): L = 0.001 / pi * T.
  for (const double albedo : {1.0, 0.7}) {
    const std::string scene = R"({"camera": {"position": [0, 0.5, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 10},
      "render": {"max_depth": 1000},
      "media": {"fog": {"type": "homogeneous", "sigma_t": 1, "albedo": )" + std::to_string(albedo) + R"(}},
      "materials": {"floor": {"type": "diffuse", "reflectance": 0.001}, "boundary": {"type": "null"}},
      "objects": [{"type": "quad", "origin": [-100, 0, -100], "edge1": [0, 0, 200], "edge2": [200, 0, 0], "material": "floor"},
                  {"type": "quad", "origin": [-100, 1, -100], "edge1": [200, 0, 0], "edge2": [0, 0, 200], "material": "boundary", "interior": "fog"},
                  {"type": "quad", "origin": [-100, 2, -100], "edge1": [0, 0, 200], "edge2": [200, 0, 0], "material": "boundary", "interior": "fog"}],
      "lights": [{"type": "directional", "direction": [0, -1, 0], "irradiance": 1}]})";
    const double T = slab_transmittance(1.0, albedo, 1000000, 5);
    INFO("albedo " << albedo << ": T " << T);
    // (Uncollided alone: e^-1 = 0.368; scattering adds to it.)
    CHECK(T > std::exp(-1.0) + 0.05);
    // No Russian roulette: after the dark floor it would keep one path in a thousand at a
    // thousand times the weight, a mean that converges from below over millions of samples.
    const Color mean = render_text(scene, "path", R"({"rr_depth": 1000})", 256, 8, 8).image.mean();
    CHECK((mean.x + mean.y + mean.z) / 3.0 == Approx(0.001 / double(kPi) * T).epsilon(0.02));
  }
}
