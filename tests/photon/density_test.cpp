// Density estimation: the progressive radius schedule and the photons' bounce window.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include "core/rng.h"
#include "io/scene_loader.h"
#include "photon/density.h"

using namespace caustica;

TEST_CASE("progressive radius: the first passes match prod (j + alpha) / (j + 1) by hand", "[photon][progressive]" TIER_UNIT) {
  for (double a : {2.0 / 3.0, 0.5, 0.9}) {
    INFO("alpha " << a);
    CHECK(progressive_radius2_scale(0, a) == 1.0);
    CHECK(progressive_radius2_scale(1, a) == Approx((1 + a) / 2).epsilon(1e-12));
    CHECK(progressive_radius2_scale(2, a) == Approx((1 + a) / 2 * (2 + a) / 3).epsilon(1e-12));
    CHECK(progressive_radius2_scale(3, a) == Approx((1 + a) / 2 * (2 + a) / 3 * (3 + a) / 4).epsilon(1e-12));
    // Strictly falling: every factor (j + alpha) / (j + 1) is below 1.
    for (int i = 1; i < 200; ++i) CHECK(progressive_radius2_scale(i, a) < progressive_radius2_scale(i - 1, a));
  }
}

TEST_CASE("progressive radius: closed form Gamma(n + 1 + a) / (Gamma(1 + a) Gamma(n + 2)), ratio to 2^(a - 1)",
          "[photon][progressive]" TIER_UNIT) {
  for (double a : {2.0 / 3.0, 0.5, 0.9}) {
    INFO("alpha " << a);
    // prod_{j=1..n} (j + a) / (j + 1) = [Gamma(n + 1 + a) / Gamma(1 + a)] / [Gamma(n + 2) / Gamma(2)].
    for (int n : {1, 5, 50, 1000, 20000}) {
      const double closed = std::exp(std::lgamma(n + 1 + a) - std::lgamma(1 + a) - std::lgamma(n + 2.0));
      INFO("pass " << n);
      CHECK(progressive_radius2_scale(n, a) == Approx(closed).epsilon(1e-9));
    }
    // It falls like C pass^(a - 1): doubling the pass count scales it by 2^(a - 1).
    const double ratio = progressive_radius2_scale(2000, a) / progressive_radius2_scale(1000, a);
    INFO("scale(2000) / scale(1000) = " << ratio << ", 2^(a-1) = " << std::pow(2.0, a - 1));
    CHECK(ratio == Approx(std::pow(2.0, a - 1)).epsilon(0.01));
  }
}

namespace {
// Photons on the plane z = 0 around the origin, arriving from +z; the flux of a photon with b
// bounces is 2^b (exact in half precision), so each bounce window has its own sum.
Photon at(float x, float y, float power, int bounces, const Vec3& side = Vec3(0, 0, 1)) {
  const Vec3 incoming = glm::normalize(side + Vec3(0.3f, -0.2f, 0.0f));
  return Photon::make(Vec3(x, y, 0), Color(power, 2 * power, 4 * power), incoming, side, bounces);
}

// Inside r = 0.5 of the origin: bounces 0..4, two photons each; outside: one each.
std::vector<Photon> window_photons() {
  std::vector<Photon> v;
  for (int b = 0; b <= 4; ++b) {
    const float p = float(1 << b);
    v.push_back(at(0.1f * float(b) - 0.2f, 0.05f, p, b));
    v.push_back(at(0.03f, 0.08f * float(b) - 0.3f, p, b));
    v.push_back(at(0.8f + 0.05f * float(b), 0.1f, 100.0f, b));  // outside the disc
  }
  // Inside the disc but from the other side of the surface: never counted.
  v.push_back(at(0.0f, 0.0f, 1000.0f, 1, Vec3(0, 0, -1)));
  return v;
}
}  // namespace

TEST_CASE("density: the bounce window keeps exactly the photons of min..max bounces (fixed radius)",
          "[photon][density]" TIER_UNIT) {
  PhotonMap map;
  map.build(window_photons(), 1.0f);
  EstimateSettings base;
  base.fixed_radius = true;
  base.max_radius = 0.5f;
  const double area = kPi * 0.25;
  std::vector<Neighbour> scratch;
  for (int lo = 0; lo <= 4; ++lo) {
    for (int hi = lo - 1; hi <= 5; ++hi) {
      const EstimateSettings s = with_bounces(base, lo, hi);
      REQUIRE(s.min_bounces == lo);
      REQUIRE(s.max_bounces == hi);
      REQUIRE(s.fixed_radius);
      double sum = 0;
      size_t count = 0;
      for (int b = std::max(lo, 0); b <= std::min(hi, 4); ++b) {
        sum += 2.0 * double(1 << b);  // two photons of flux 2^b inside the disc
        count += 2;
      }
      EstimateInfo info;
      const Color E = irradiance_estimate(map, Vec3(0), Vec3(0, 0, 1), s, scratch, &info);
      INFO("window [" << lo << ", " << hi << "]: E " << E.x << " " << E.y << " " << E.z << ", expected "
                      << sum / area);
      CHECK(info.photons == count);
      CHECK(info.radius == Approx(0.5f));
      CHECK(E.x == Approx(sum / area).epsilon(1e-5));
      CHECK(E.y == Approx(2 * sum / area).epsilon(1e-5));
      CHECK(E.z == Approx(4 * sum / area).epsilon(1e-5));
    }
  }
  // The default window admits every bounce count.
  EstimateInfo info;
  const Color all = irradiance_estimate(map, Vec3(0), Vec3(0, 0, 1), base, scratch, &info);
  CHECK(info.photons == 10);
  CHECK(all.x == Approx(2.0 * 31.0 / area).epsilon(1e-5));
}

TEST_CASE("density: radiance estimate with a bounce window is f_r times the kept flux over pi r^2",
          "[photon][density]" TIER_UNIT) {
  // A diffuse quad in z = 0 seen from +z: f_r = albedo / pi.
  LoadedScene s = parse_scene(R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
    "materials": {"m": {"type": "diffuse", "albedo": [0.5, 0.25, 0.75]}},
    "objects": [{"type": "quad", "origin": [-2, -2, 0], "edge1": [4, 0, 0], "edge2": [0, 4, 0], "material": "m"}],
    "lights": [{"type": "point", "position": [0, 0, 2], "intensity": 1}]})",
                              "quad.json", ".");
  SurfaceHit hit;
  REQUIRE(s.scene->intersect(Ray{Vec3(0, 0, 3), Vec3(0, 0, -1)}, hit));
  const Vec3 wo(0, 0, 1);
  const Vec3 side = glm::dot(wo, hit.n) >= 0 ? hit.n : -hit.n;
  REQUIRE(side.z > 0.99f);
  PhotonMap map;
  map.build(window_photons(), 1.0f);
  EstimateSettings est;
  est.fixed_radius = true;
  est.max_radius = 0.5f;
  std::vector<Neighbour> scratch;
  EstimateInfo info;
  const Color L = radiance_estimate(map, hit, wo, with_bounces(est, 1, 3), scratch, &info);
  const double flux = 2.0 * (2 + 4 + 8);  // bounces 1, 2, 3, two photons each
  const double area = kPi * 0.25;
  CHECK(info.photons == 6);
  CHECK(L.x == Approx(0.5 / kPi * flux / area).epsilon(1e-5));
  CHECK(L.y == Approx(0.25 / kPi * 2 * flux / area).epsilon(1e-5));
  CHECK(L.z == Approx(0.75 / kPi * 4 * flux / area).epsilon(1e-5));
  // An empty window: nothing.
  const Color none = radiance_estimate(map, hit, wo, with_bounces(est, 3, 2), scratch, &info);
  CHECK(info.photons == 0);
  CHECK(none == Color(0.0f));
}

TEST_CASE("density: k-NN estimate with a bounce window keeps the disc of the k nearest of any bounce count",
          "[photon][density]" TIER_UNIT) {
  // On the x axis at 0.1, 0.2, ..., 0.6 with bounces 0, 1, 2, 0, 1, 2; flux 1 each.
  std::vector<Photon> v;
  for (int i = 0; i < 6; ++i) v.push_back(at(0.1f * float(i + 1), 0.0f, 1.0f, i % 3));
  PhotonMap map;
  map.build(v, 1.0f);
  EstimateSettings s;
  s.k = 4;  // the four nearest: at 0.1 .. 0.4, of bounces 0, 1, 2, 0; the one at 0.4 is the rim
  s.max_radius = 10.0f;
  std::vector<Neighbour> scratch;
  EstimateInfo info;
  const Color E = irradiance_estimate(map, Vec3(0), Vec3(0, 0, 1), with_bounces(s, 1, 2), scratch, &info);
  const double r = 0.4;
  CHECK(info.photons == 2);  // bounces 1 and 2 among the four nearest
  CHECK(info.radius == Approx(r).epsilon(1e-5));
  CHECK(E.x == Approx(2.0 / (kPi * r * r)).epsilon(1e-4));
  // Bounce 0 only: the photon at 0.1 over the same disc (the one at 0.4 defines the rim and, as
  // the k-th, is not inside it).
  const Color E0 = irradiance_estimate(map, Vec3(0), Vec3(0, 0, 1), with_bounces(s, 0, 0), scratch, &info);
  CHECK(info.photons == 1);
  CHECK(info.radius == Approx(r).epsilon(1e-5));
  CHECK(E0.x == Approx(1.0 / (kPi * r * r)).epsilon(1e-4));
}

namespace {
// The mean, over many maps of n photons of flux 1 spread uniformly over [-1, 1]^2, of the
// irradiance estimate at 25 well separated points, over the true density n / 4.
double mean_uniform_estimate(const EstimateSettings& s, size_t n, int maps) {
  Rng rng(77);
  std::vector<Neighbour> scratch;
  double sum = 0;
  int count = 0;
  for (int m = 0; m < maps; ++m) {
    std::vector<Photon> v;
    v.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      const float x = 2 * rng.next_float() - 1, y = 2 * rng.next_float() - 1;
      v.push_back(at(x, y, 1.0f, 0));
    }
    PhotonMap map;
    map.build(std::move(v), 1.0f);
    for (int qy = -2; qy <= 2; ++qy) {
      for (int qx = -2; qx <= 2; ++qx) {
        sum += irradiance_estimate(map, Vec3(0.3f * qx, 0.3f * qy, 0), Vec3(0, 0, 1), s, scratch).x;
        ++count;
      }
    }
  }
  return sum / count / (double(n) / 4.0);
}
}  // namespace

TEST_CASE("density: a fixed-radius estimate of a uniform photon density is unbiased", "[photon][density]" TIER_UNIT) {
  EstimateSettings s;
  s.fixed_radius = true;
  s.max_radius = 0.06f;  // about 11 photons on average
  const double ratio = mean_uniform_estimate(s, 4000, 100);
  INFO("mean estimate / true density " << ratio);
  CHECK(ratio == Approx(1.0).margin(0.02));  // standard error about 0.006
}

// Jensen's estimate summed the k nearest photons over the disc through the k-th: for a uniform
// density its expectation is k / (k - 1) times the density (pi r_k^2 is Gamma(k) distributed),
// 11 % high at k = 10, 2 % at the photon integrator's global_k 50. The estimate now counts the
// k - 1 photons inside the disc, which is unbiased.
TEST_CASE("density: a k-NN estimate of a uniform photon density is unbiased", "[photon][density]" TIER_UNIT) {
  EstimateSettings s;
  s.k = 10;
  s.max_radius = 1.0f;
  const double ratio = mean_uniform_estimate(s, 4000, 100);
  INFO("mean estimate / true density " << ratio << " (k / (k - 1) = " << 10.0 / 9.0 << ")");
  CHECK(ratio == Approx(1.0).margin(0.03));
}

namespace {
// The mean over `maps` maps of `photons` photons of flux 1, placed on [-1, 1]^2 by place(rng),
// of the precomputed irradiance (1 in 4 photons a site, as the photon integrator builds it)
// read at `points`, each over `density` there; and the standard error of that mean, from the
// spread of the maps' means.
template <class Place, class Density>
std::pair<double, double> mean_cached(const EstimateSettings& s, size_t photons, int maps, Place place,
                                      const std::vector<Vec3>& points, Density density) {
  Rng rng(91);
  std::vector<Neighbour> scratch;
  std::vector<double> per_map;
  for (int m = 0; m < maps; ++m) {
    std::vector<Photon> v;
    for (size_t i = 0; i < photons; ++i) {
      const Vec2 xy = place(rng);
      v.push_back(at(xy.x, xy.y, 1.0f, 0));
    }
    PhotonMap map;
    map.build(std::move(v), 1.0f);
    IrradianceCache cache;
    cache.build(map, 4, s);
    double sum = 0;
    for (const Vec3& q : points) {
      Color E;
      REQUIRE(cache.lookup(q, Vec3(0, 0, 1), 0.5f, 0, E, scratch));
      sum += double(E.x) / density(q);
    }
    per_map.push_back(sum / double(points.size()));
  }
  double mean = 0, ss = 0;
  for (double x : per_map) mean += x / maps;
  for (double x : per_map) ss += (x - mean) * (x - mean);
  return {mean, std::sqrt(ss / (maps - 1) / maps)};
}
}  // namespace

// The precomputed irradiance, read by lookups at points between its sites, on a uniform photon
// density: its mean is the density at every disc size a progressive render reaches (a site's
// estimate leaves out the sites, so neither its own photon nor the sites' emptiness around a
// lookup biases it). (Sites that were every 4th photon, estimated from all photons, read 1.046
// at k = 50 and radius2_scale 0.1, 1.27 at k = 10 and 0.2.)
TEST_CASE("density: the precomputed irradiance reads a uniform density without bias at any disc size",
          "[photon][density][progressive]" TIER_UNIT) {
  std::vector<Vec3> points;
  for (int qy = -2; qy <= 2; ++qy)
    for (int qx = -2; qx <= 2; ++qx) points.emplace_back(0.3f * qx + 0.01f, 0.3f * qy, 0.0f);
  constexpr size_t kPhotons = 4000;
  for (const int k : {10, 20, 50})
    for (const float scale : {1.0f, 0.5f, 0.2f, 0.1f, 0.05f}) {
      EstimateSettings s;
      s.k = size_t(k);
      s.max_radius = 1.0f;
      s.radius2_scale = scale;
      // (Fewer photons in the smallest discs: more maps, for a standard error of about 2 %.)
      const int maps = scale < 0.2f ? 160 : 40;
      const auto [ratio, se] = mean_cached(s, kPhotons, maps, [](Rng& rng) { return Vec2(2 * rng.next_float() - 1, 2 * rng.next_float() - 1); },
                                           points, [](const Vec3&) { return double(kPhotons) / 4.0; });
      INFO("k " << k << ", radius2_scale " << scale << ": mean cached irradiance / true density " << ratio
                << " (standard error " << se << ")");
      CHECK(std::abs(ratio - 1.0) < std::max(0.015, 4.0 * se));
    }
}

// Where the density falls to zero (a contact shadow), the nearest site of a lookup lies more
// often on the bright side: sites are photons. Carried along the gradient measured at the site,
// the cache reads what the full k-NN estimate reads at the lookup's point (itself biased there:
// its disc crosses the edge; the sites' estimates, from 3/4 of the photons, smooth a little
// more: 0.97 to 1.02 of it). Without the gradient it read 1.15 of it at x = -0.85, and
// Mitsuba's principled scene's contact shadows were 4 % too bright.
TEST_CASE("density: the precomputed irradiance reads a steep density gradient as the full estimate does",
          "[photon][density]" TIER_UNIT) {
  constexpr size_t kPhotons = 4000;
  constexpr int kMaps = 100;
  EstimateSettings s;
  s.k = 50;
  s.max_radius = 1.0f;
  for (const float x : {-0.85f, -0.7f, -0.4f}) {
    Rng rng(5);
    std::vector<Neighbour> scratch;
    std::vector<double> per_map;
    for (int m = 0; m < kMaps; ++m) {
      // Density n (x + 1) / 4 on [-1, 1]^2: x = 2 sqrt(u) - 1.
      std::vector<Photon> v;
      for (size_t i = 0; i < kPhotons; ++i) v.push_back(at(2 * std::sqrt(rng.next_float()) - 1, 2 * rng.next_float() - 1, 1.0f, 0));
      PhotonMap map;
      map.build(std::move(v), 1.0f);
      IrradianceCache cache;
      cache.build(map, 4, s);
      double cached = 0, full = 0;
      for (int qy = -3; qy <= 3; ++qy) {
        const Vec3 q(x + 0.007f * qy, 0.11f * qy, 0.0f);
        Color E;
        REQUIRE(cache.lookup(q, Vec3(0, 0, 1), 0.5f, 0, E, scratch));
        cached += double(E.x);
        full += double(irradiance_estimate(map, q, Vec3(0, 0, 1), s, scratch).x);
      }
      per_map.push_back(cached / full);
    }
    double mean = 0, ss = 0;
    for (double r : per_map) mean += r / kMaps;
    for (double r : per_map) ss += (r - mean) * (r - mean);
    const double se = std::sqrt(ss / (kMaps - 1) / kMaps);
    INFO("x " << x << ": cached / full estimate " << mean << " (standard error " << se << ")");
    CHECK(std::abs(mean - 1.0) < std::max(0.04, 4.0 * se));
  }
}
