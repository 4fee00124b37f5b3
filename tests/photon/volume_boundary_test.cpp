// The volume photons' boundary correction: the fraction of a ball in a photon's medium against
// the analytic fraction a plane leaves of it.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "core/scene.h"
#include "io/scene_loader.h"
#include "photon/volume_boundary.h"

using namespace caustica;

namespace {
// The part of a ball of radius r whose centre lies h (0 <= h <= r) from a plane, on its side.
double plane_fraction(double h, double r) { return 1.0 - (r - h) * (r - h) * (2.0 * r + h) / (4.0 * r * r * r); }

// The mean of many estimates (each in its own random orientation).
double mean_fraction(const Scene& scene, const Vec3& p, int32_t medium, float r) {
  constexpr int kRuns = 4000;
  double sum = 0;
  uint64_t rays = 0;
  for (int i = 0; i < kRuns; ++i) {
    Rng rng(hash_seed(uint64_t(i), 17));
    sum += medium_ball_fraction(scene, p, medium, r, kBoundaryDirections, rng, rays);
  }
  return sum / kRuns;
}
}  // namespace

TEST_CASE("volume boundary: the ball's fraction beside a wall, across a null boundary and in a medium's bounds",
          "[photon][volume][media]" TIER_UNIT) {
  // Fog everywhere; an opaque floor at y = 0 and, above it, a surface that only bounds media
  // (null BSDF): the floor cuts the ball, the boundary does not.
  LoadedScene open = parse_scene(R"({"camera": {"position": [0, 5, -10], "look_at": [0, 0, 0], "medium": "fog"},
    "media": {"fog": {"type": "homogeneous", "sigma_t": 1}},
    "materials": {"floor": {"type": "diffuse"}, "boundary": {"type": "null"}},
    "objects": [{"type": "mesh", "material": "floor", "vertices": [[-50, 0, -50], [50, 0, -50], [50, 0, 50], [-50, 0, 50]],
                 "indices": [[0, 2, 1], [0, 3, 2]]},
                {"type": "sphere", "center": [0, 0.6, 0], "radius": 0.2, "material": "boundary", "interior": "fog", "exterior": "fog"}]})",
                                 "open.json", ".");
  const Scene& scene = *open.scene;
  const int32_t fog = scene.camera_medium;
  REQUIRE(fog >= 0);
  for (double h : {0.1, 0.4, 0.7, 1.0, 1.3}) {
    INFO("h = " << h);
    CHECK(mean_fraction(scene, Vec3(0.0f, float(h), 0.0f), fog, 1.0f) == Approx(plane_fraction(std::min(h, 1.0), 1.0)).margin(0.004));
  }
  // A medium bounded by a large null sphere, the point inside it h from its shell: the far
  // side (another medium) is outside the ball's fraction, nearly as beyond a plane.
  LoadedScene bounded = parse_scene(R"({"camera": {"position": [0, 0, -200], "look_at": [0, 0, 0]},
    "media": {"fog": {"type": "homogeneous", "sigma_t": 1}, "haze": {"type": "homogeneous", "sigma_t": 0.1}},
    "materials": {"boundary": {"type": "null"}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 100, "material": "boundary", "interior": "fog", "exterior": "haze"}]})",
                                    "bounded.json", ".");
  const Scene& ball = *bounded.scene;
  const int32_t inside = ball.medium_at(Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f));
  REQUIRE(inside >= 0);
  const double h = 0.5;
  CHECK(mean_fraction(ball, Vec3(0.0f, float(100.0 - h), 0.0f), inside, 1.0f) == Approx(plane_fraction(h, 1.0)).margin(0.006));
  // Far from any surface: the whole ball, in every orientation.
  Rng rng(3);
  uint64_t rays = 0;
  CHECK(medium_ball_fraction(ball, Vec3(0.0f), inside, 1.0f, kBoundaryDirections, rng, rays) == Approx(1.0).margin(1e-5));
  CHECK(rays == uint64_t(kBoundaryDirections));
}
