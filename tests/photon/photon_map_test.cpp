// The kd-tree against a brute-force scan, and the photon record's encodings.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include "core/rng.h"
#include "core/sampling.h"
#include "photon/photon_map.h"

using namespace caustica;

namespace {
std::vector<Photon> random_photons(size_t n, uint64_t seed) {
  Rng rng(seed);
  std::vector<Photon> v;
  for (size_t i = 0; i < n; ++i) {
    // Clustered like real maps: half on a plane, half in a blob.
    Vec3 p(rng.next_float(), rng.next_float(), rng.next_float());
    if (i % 2) p.y = 0.25f;
    else p = Vec3(0.5f) + 0.05f * (p - Vec3(0.5f));
    v.push_back(Photon::make(p, Color(1, 2, 3), Vec3(0, 1, 0), Vec3(0, 1, 0), 0));
  }
  return v;
}
}  // namespace

TEST_CASE("photon map: knn and radius queries match a brute-force scan", "[photon][kdtree]" TIER_UNIT) {
  const auto photons = random_photons(20000, 11);
  PhotonMap map;
  map.build(photons, 1.0f);
  REQUIRE(map.size() == photons.size());
  Rng rng(5);
  std::vector<Neighbour> found;
  std::vector<std::pair<float, uint32_t>> all;
  for (int q = 0; q < 300; ++q) {
    const Vec3 p(rng.next_float(), rng.next_float() * 0.5f + 0.1f, rng.next_float());
    all.clear();
    for (uint32_t i = 0; i < photons.size(); ++i) {
      const Vec3 d = map[i].position - p;
      all.emplace_back(glm::dot(d, d), i);
    }
    std::sort(all.begin(), all.end());
    for (size_t k : {1, 10, 50, 100}) {
      for (float max_r : {0.02f, 0.1f, 10.0f}) {
        map.knn(p, k, max_r, found);
        size_t expected = 0;
        while (expected < k && expected < all.size() && all[expected].first < max_r * max_r) ++expected;
        REQUIRE(found.size() == expected);
        for (size_t j = 0; j < found.size(); ++j) {
          CHECK(found[j].dist2 == Approx(all[j].first).margin(1e-9));  // same distances, nearest first
        }
      }
    }
    const float radius = 0.03f;
    map.radius_query(p, radius, found);
    std::vector<uint32_t> got, want;
    for (const auto& nb : found) got.push_back(nb.index);
    for (const auto& a : all)
      if (a.first < radius * radius) want.push_back(a.second);
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    REQUIRE(got == want);
  }
}

TEST_CASE("photon map: empty map answers nothing", "[photon][kdtree]" TIER_UNIT) {
  PhotonMap map;
  map.build({}, 1.0f);
  std::vector<Neighbour> found;
  CHECK(map.knn(Vec3(0), 10, 1.0f, found) == 0);
  CHECK(map.radius_query(Vec3(0), 1.0f, found) == 0);
}

TEST_CASE("photon record: 24 bytes, directions within 1.5 degrees, flux to half precision", "[photon]" TIER_UNIT) {
  STATIC_REQUIRE(sizeof(Photon) == 24);
  Rng rng(3);
  float worst = 1;
  for (int i = 0; i < 100000; ++i) {
    const Vec3 d = sample_uniform_sphere(Vec2(rng.next_float(), rng.next_float()));
    worst = std::min(worst, glm::dot(d, decode_direction(encode_direction(d))));
  }
  CHECK(worst > std::cos(1.5f * kPi / 180.0f));
  for (const Vec3& axis : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0)}) {
    CHECK(glm::dot(axis, decode_direction(encode_direction(axis))) > 0.9995f);
  }
  const Photon p = Photon::make(Vec3(1, 2, 3), Color(0.123f, 1.0f, 7.5f), Vec3(0, 0, 1), Vec3(0, 1, 0), 2);
  CHECK(p.power().x == Approx(0.123f).epsilon(1e-3));
  CHECK(p.power().z == Approx(7.5f).epsilon(1e-3));
  CHECK(p.bounces == 2);
}

TEST_CASE("photon map: memory stays near 32 bytes a photon", "[photon][kdtree]" TIER_UNIT) {
  PhotonMap map;
  map.build(random_photons(200000, 2), 1.0f);
  const double per_photon = double(map.memory_bytes()) / double(map.size());
  INFO("bytes per photon " << per_photon);
  CHECK(per_photon >= 28.0);  // 24 of record + 4 of index at least
  CHECK(per_photon <= 32.0);  // the target of the photon-mapping issue
}

TEST_CASE("photon map: a large map (two kd-trees) still matches a brute-force scan", "[photon][kdtree]" TIER_UNIT) {
  const auto photons = random_photons(PhotonMap::kSplitThreshold + 1000, 23);
  PhotonMap map;
  map.build(photons, 1.0f);
  REQUIRE(map.size() == photons.size());
  Rng rng(8);
  std::vector<Neighbour> found;
  std::vector<std::pair<float, uint32_t>> all(map.size());
  for (int q = 0; q < 40; ++q) {
    // Queries near the plane, in the blob, and far outside both halves' boxes.
    const Vec3 p = q % 4 == 3 ? Vec3(3.0f, rng.next_float(), -2.0f)
                              : Vec3(rng.next_float(), rng.next_float() * 0.5f + 0.1f, rng.next_float());
    for (uint32_t i = 0; i < map.size(); ++i) {
      const Vec3 d = map[i].position - p;
      all[i] = {glm::dot(d, d), i};
    }
    std::partial_sort(all.begin(), all.begin() + 60, all.end());
    map.knn(p, 50, 10.0f, found);
    REQUIRE(found.size() == 50);
    for (size_t j = 0; j < found.size(); ++j) CHECK(found[j].dist2 == Approx(all[j].first).margin(1e-9));
    const float radius = 0.02f;
    map.radius_query(p, radius, found);
    size_t expected = 0;
    for (const auto& a : all) expected += a.first < radius * radius;
    CHECK(found.size() == expected);
    for (const auto& nb : found) CHECK(glm::dot(map[nb.index].position - p, map[nb.index].position - p) < radius * radius);
  }
  CHECK(double(map.memory_bytes()) / double(map.size()) <= 32.0);
}
