// Lights rendered: analytic irradiance from spot and directional lights on a floor, a constant
// environment around a sphere, in the path tracer and photon mapping; photon flux of a
// directional light.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "support/scenes.h"
#include "io/scene_loader.h"
#include "photon/photon_tracer.h"
#include "support/render_util.h"
#include "support/temp_dir.h"
#include "io/image_io.h"

using namespace caustica;
using test::floor_scene;
using test::render_text;

TEST_CASE("spot light: a floor on the axis reads rho / pi * I / h^2", "[trace][light]" TIER_UNIT) {
  // Spot 2 units above the floor pointing down; the camera sees the floor around the axis.
  const std::string scene = floor_scene(
      R"({"type": "spot", "position": [0, 2, 0], "target": [0, 0, 0], "intensity": [8, 4, 2], "cutoff_angle": 20})");
  const auto r = render_text(scene, "path", "{}", 4, 8, 8);
  const Color mean = r.image.mean();
  // E = I / h^2 (the floor within 0.1 units of the axis: cos^3 > 0.99).
  for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(0.5 / 3.14159265358979 * (8 >> c) / 4.0).epsilon(0.01));
}

TEST_CASE("directional light: a floor reads rho / pi * E cos(theta), in path and photon", "[trace][light]" TIER_UNIT) {
  // Light travelling down at 60 degrees from the normal: E cos(theta) = E / 2.
  const std::string scene = floor_scene(
      R"({"type": "directional", "direction": [0.8660254, -0.5, 0], "irradiance": [6, 3, 1.5]})");
  for (const char* integrator : {"path", "photon"}) {
    INFO(integrator);
    const auto r = render_text(scene, integrator, "{}", 4, 8, 8);
    const Color mean = r.image.mean();
    // Nothing else in the scene reflects light back: the floor sees the light only.
    for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(0.5 / 3.14159265358979 * 3.0 / double(1 << c)).epsilon(0.01));
  }
}

TEST_CASE("directional light: photons on a floor carry E times the floor's projected area", "[photon][light]" TIER_UNIT) {
  const std::string scene = floor_scene(R"({"type": "directional", "direction": [0, -1, 0], "irradiance": [2, 2, 2]})");
  LoadedScene s = parse_scene(scene, "floor.json", ".");
  PhotonPassSettings settings;
  settings.global_photons = 100000;
  settings.caustic_photons = 0;
  const PhotonPassResult r = trace_photons(*s.scene, settings);
  glm::dvec3 sum(0.0);
  for (const Photon& p : r.global) {
    if (p.bounces == 0) sum += glm::dvec3(p.power() * r.global_scale);
  }
  // The floor is 100 x 100; a single plane reflects nothing back onto itself.
  CHECK(sum.x == Approx(2.0 * 100 * 100).epsilon(0.02));
}

TEST_CASE("constant environment: a diffuse sphere reads rho L, the background L, in path and photon",
          "[trace][light]" TIER_UNIT) {
  // A convex object under a uniform sky: every point sees the sky over its whole hemisphere.
  const std::string scene = R"({
    "camera": {"position": [0, 0, -4], "look_at": [0, 0, 0], "fov": 10},
    "materials": {"ball": {"type": "diffuse", "reflectance": 0.6}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "ball"}],
    "lights": [{"type": "constant", "radiance": [2, 1, 0.5]}]})";
  for (const char* integrator : {"path", "photon"}) {
    INFO(integrator);
    const auto r = render_text(scene, integrator, "{}", 16, 8, 8);
    // The camera sees only the sphere (fov 10 degrees at distance 4).
    const Color mean = r.image.mean();
    CHECK(mean.x == Approx(1.2).epsilon(0.02));
    CHECK(mean.z == Approx(0.3).epsilon(0.02));
  }
  // Two environments at once: multiple importance sampling weighs each against its own
  // light-sampling density, so the sphere still reads rho (L1 + L2).
  std::string two = scene;
  two.replace(two.find(R"({"type": "constant", "radiance": [2, 1, 0.5]})"), 45,
              R"({"type": "constant", "radiance": [1, 0.5, 0.25]}, {"type": "constant", "radiance": [1, 0.5, 0.25]})");
  for (const char* integrator : {"path", "photon"}) {
    INFO(integrator << ", two environments");
    const Color mean = render_text(two, integrator, "{}", 16, 8, 8).image.mean();
    CHECK(mean.x == Approx(1.2).epsilon(0.02));
  }
  const std::string sky = R"({
    "camera": {"position": [0, 0, -4], "look_at": [0, 0, -10], "fov": 10},
    "materials": {"ball": {"type": "diffuse", "reflectance": 0.6}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "ball"}],
    "lights": [{"type": "constant", "radiance": [2, 1, 0.5]}]})";
  const auto r = render_text(sky, "photon", "{}", 1, 4, 4);
  CHECK(r.image.mean().y == Approx(1.0f));
}

TEST_CASE("mask: a quarter-opaque blocker passes three quarters of the light, in path and photon", "[trace][mask]" TIER_FIGURE) {
  // A directional light straight down; a masked quad (opacity 0.25, black BSDF) hovers over the
  // part of the floor the camera sees. The floor reads rho / pi * E * 0.75.
  const std::string scene = R"({
    "camera": {"position": [0, 4, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 2},
    "materials": {"floor": {"type": "diffuse", "reflectance": 0.5},
                  "veil": {"type": "mask", "opacity": 0.25, "bsdf": {"type": "diffuse", "reflectance": 0}}},
    "objects": [{"type": "quad", "origin": [-50, 0, -50], "edge1": [0, 0, 100], "edge2": [100, 0, 0], "material": "floor"},
                {"type": "quad", "origin": [-5, 1, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0], "material": "veil"}],
    "lights": [{"type": "directional", "direction": [0, -1, 0], "irradiance": 4}]})";
  for (const char* integrator : {"path", "photon"}) {
    INFO(integrator);
    // photon: 1024 progressive passes, each with small maps (the light is one direction).
    const auto r = render_text(scene, integrator, std::string(integrator) == "photon" ? R"({"photons": 2000, "caustic_photons": 2000})" : "{}", 1024, 8, 8);
    // Camera rays also cross the veil: 0.75 of them reach the floor, which gets 0.75 of the light.
    CHECK(r.image.mean().x == Approx(0.5 / 3.14159265358979 * 4.0 * 0.75 * 0.75).epsilon(0.03));
  }
}

namespace {
// A floor seen from 4 above (image left = world +x, image top = world +z), lit by `light`; a 2 x 1
// image file of two texels (left, right) for the light's texture.
std::string lit_floor(const std::string& light) {
  return R"({"camera": {"position": [0, 4, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 20},
    "materials": {"floor": {"type": "diffuse", "reflectance": 0.5}},
    "objects": [{"type": "quad", "origin": [-50, 0, -50], "edge1": [0, 0, 100], "edge2": [100, 0, 0], "material": "floor"}],
    "lights": [)" + light + "]}";
}
std::string two_texels(const test::TempDir& dir, const Color& left, const Color& right) {
  Image img(2, 1);
  img.pixels = {left, right};
  const std::string path = dir.file("two.exr");
  write_image(path, img);
  return path;
}
}  // namespace

TEST_CASE("projector: a floor reads scale E / h^2 where the image falls, the image as a camera there sees it", "[trace][light]" TIER_UNIT) {
  test::TempDir dir;
  const std::string image = two_texels(dir, Color(0.8f, 0.2f, 0.2f), Color(0.2f, 0.2f, 0.8f));
  // 2 above the floor, looking down, up +z: the image's left (u < 1/2) falls on world +x. A
  // perpendicular plane at distance h gets irradiance pi scale E / h^2 everywhere: a diffuse
  // floor of 0.5 reads 0.5 scale E / h^2 = E / 4 with scale 2.
  const std::string scene = lit_floor(R"({"type": "projector", "position": [0, 2, 0], "target": [0, 0, 0], "up": [0, 0, 1],
      "fov": 40, "scale": 2, "irradiance": {"type": "bitmap", "filename": ")" + image + R"(", "filter_type": "nearest"}})");
  for (const char* integrator : {"path", "photon"}) {
    INFO(integrator);
    const auto r = render_text(scene, integrator, R"({})", 16, 16, 16);
    const glm::dvec3 left = test::region_mean(r.image, 1, 6, 7, 10), right = test::region_mean(r.image, 9, 6, 15, 10);
    CHECK(left.x == Approx(0.8 / 4).epsilon(0.02));
    CHECK(left.z == Approx(0.2 / 4).epsilon(0.02));
    CHECK(right.x == Approx(0.2 / 4).epsilon(0.02));
    CHECK(right.z == Approx(0.8 / 4).epsilon(0.02));
    // Outside the image (the aspect is 2: z beyond 2 tan 20 / 2 = 0.36), dark.
    CHECK(test::region_mean(r.image, 0, 0, 16, 2).x < 1e-3);
  }
}

TEST_CASE("spot light: a texture on the cone, the right way round and of the right value", "[trace][light]" TIER_UNIT) {
  test::TempDir dir;
  const std::string image = two_texels(dir, Color(1.0f, 0.0f, 0.0f), Color(0.0f, 0.0f, 1.0f));
  // Mitsuba's spot maps u = 1/2 + x / (2 z tan cutoff), x = cross(up, axis) = world +x here: the
  // right texel (u > 1/2) falls on world +x, the image's left. Within 0.26 of the axis,
  // cos^3 > 0.97: E = I / h^2.
  const std::string scene = lit_floor(R"({"type": "spot", "position": [0, 2, 0], "target": [0, 0, 0], "up": [0, 0, 1],
      "intensity": 4, "cutoff_angle": 30, "beam_width": 30,
      "texture": {"type": "bitmap", "filename": ")" + image + R"(", "filter_type": "nearest"}})");
  const auto r = render_text(scene, "path", "{}", 16, 16, 16);
  const glm::dvec3 left = test::region_mean(r.image, 5, 7, 7, 9), right = test::region_mean(r.image, 9, 7, 11, 9);
  const double expected = 0.5 / 3.14159265358979 * 4.0 / 4.0;
  CHECK(left.z == Approx(expected).epsilon(0.03));
  CHECK(left.x < 1e-4);
  CHECK(right.x == Approx(expected).epsilon(0.03));
  CHECK(right.z < 1e-4);
  // The photon integrator (direct light by the same shadow rays) agrees.
  const auto pm = render_text(scene, "photon", "{}", 16, 16, 16);
  CHECK(test::region_mean(pm.image, 0, 0, 16, 16).x == Approx(test::region_mean(r.image, 0, 0, 16, 16).x).epsilon(0.02));
}
