// The volume photon map's search along rays against a brute-force scan, and its first radius
// on a lattice of known spacing.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include <map>
#include "core/sampler.h"
#include "photon/volume_map.h"

using namespace caustica;

TEST_CASE("volume map: the photons along a ray are those a brute-force scan finds, with their t and distance",
          "[photon][volume]" TIER_UNIT) {
  Rng rng(17);
  std::vector<Photon> photons;
  for (int i = 0; i < 5000; ++i) {
    // Clustered and spread: a dense ball and a sparse box.
    const Vec3 p = i % 3 == 0 ? Vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 0.3f + Vec3(0.4f)
                              : Vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 2.0f - Vec3(0.5f);
    photons.push_back(Photon::make(p, Color(1.0f), Vec3(0, 0, 1), Vec3(0, 0, 1), i % 4));
  }
  VolumePhotonMap map;
  map.build(photons, 2.0f);
  REQUIRE(map.size() == photons.size());
  CHECK(map.photons().power(0).x == Approx(2.0f).epsilon(1e-3));
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 o = Vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 3.0f - Vec3(1.0f);
    Vec3 d = Vec3(rng.next_float(), rng.next_float(), rng.next_float()) - Vec3(0.5f);
    if (trial % 10 == 0) d = Vec3(0.0f, 1.0f, 0.0f);  // (along an axis: zero direction components)
    d = glm::normalize(d);
    const Ray ray{o, d, kInfinity};
    const float tmax = trial % 5 == 0 ? kInfinity : 3.0f * rng.next_float();
    const float radius = 0.01f + 0.2f * rng.next_float();
    std::map<uint32_t, std::pair<float, float>> found;
    map.along(ray, 0.0f, tmax, radius, [&](uint32_t i, float t, float d2) { found[i] = {t, d2}; });
    size_t expected = 0;
    for (uint32_t i = 0; i < map.size(); ++i) {
      const Vec3 v = map.photons()[i].position - o;
      const float t = glm::dot(v, d);
      const float d2 = glm::dot(v, v) - t * t;
      // (Photons within rounding of the cylinder's edge may go either way.)
      const bool inside = t >= 0.0f && t <= tmax && d2 < radius * radius;
      const bool edge = std::abs(d2 - radius * radius) < 1e-5f || std::abs(t) < 1e-5f || std::abs(t - tmax) < 1e-5f;
      if (edge) continue;
      if (inside) {
        ++expected;
        REQUIRE(found.count(i) == 1);
        CHECK(found[i].first == Approx(t).margin(1e-5));
        CHECK(found[i].second == Approx(d2).margin(1e-5));
      } else {
        CHECK(found.count(i) == 0);
      }
    }
    CHECK(found.size() >= expected);
  }
}

TEST_CASE("volume map: the first radius on a lattice is its spacing", "[photon][volume]" TIER_UNIT) {
  // Spacing 0.1: a photon's 6 nearest others lie at 0.1, the next 12 at 0.1 sqrt(2).
  std::vector<Photon> photons;
  for (int x = 0; x < 20; ++x)
    for (int y = 0; y < 20; ++y)
      for (int z = 0; z < 20; ++z)
        photons.push_back(Photon::make(Vec3(float(x), float(y), float(z)) * 0.1f, Color(1.0f), Vec3(0, 0, 1), Vec3(0, 0, 1), 1));
  VolumePhotonMap map;
  map.build(photons, 1.0f);
  CHECK(map.median_knn_radius(6) == Approx(0.1f).epsilon(1e-3));
  CHECK(map.median_knn_radius(18) == Approx(0.1f * std::sqrt(2.0f)).epsilon(1e-3));
  CHECK(VolumePhotonMap().median_knn_radius(6) == 0.0f);
}
