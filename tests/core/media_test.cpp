// Participating media: phase functions against their densities (chi-square), the homogeneous
// medium's transmittance and free-flight sampling against their integrals.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include "core/media/heterogeneous.h"
#include "core/media/homogeneous.h"
#include "core/media/phase.h"
#include "support/grids.h"
#include "support/chi2.h"

using namespace caustica;

namespace {
constexpr int kChi2Tests = 6;
const double kAlpha = test::sidak_alpha(0.01, kChi2Tests);
}  // namespace

TEST_CASE("media: Henyey-Greenstein and isotropic sampling match their densities (chi-square), and HG's mean "
          "cosine is g",
          "[core][media][chi2]" TIER_UNIT) {
  const Vec3 wo = glm::normalize(Vec3(0.3f, -0.5f, 0.8f));
  auto check = [&](const PhaseFunction& phase, uint64_t seed) {
    constexpr int n = 200000;
    test::SphereHistogram hist(40, 40);
    Rng rng(seed);
    double mean_cos = 0, worst_pdf = 0;
    for (int i = 0; i < n; ++i) {
      Vec3 wi;
      const Vec2 u(rng.next_float(), rng.next_float());
      const float pdf = phase.sample(wo, u, wi);
      hist.add(wi);
      mean_cos += double(glm::dot(-wo, wi));
      worst_pdf = std::max(worst_pdf, std::abs(double(pdf) / double(phase.eval(wo, wi)) - 1.0));
    }
    const auto expected = hist.expected([&](const Vec3& w) { return double(phase.eval(wo, w)); }, n);
    INFO("expected mass " << test::sum(expected) / n);
    CHECK(test::sum(expected) / n == Approx(1.0).epsilon(0.002));
    const test::Chi2Result r = test::chi2_test(hist.counts(), expected);
    INFO(r.message);
    CHECK(r.accepts(kAlpha));
    CHECK(worst_pdf < 1e-4);  // sample() returns the density eval() gives
    CHECK(mean_cos / n == Approx(phase.mean_cosine()).margin(0.006));
  };
  uint64_t seed = 1;
  for (float g : {-0.8f, -0.3f, 0.0f, 0.5f, 0.85f}) {
    INFO("g " << g);
    check(HenyeyGreenstein(g), seed++);
  }
  check(IsotropicPhase(), seed++);
}

TEST_CASE("media: a homogeneous medium's transmittance is Beer-Lambert's, and free-flight sampling's weights average "
          "to the transmittance (passing) and to the scattered part albedo (1 - Tr) (scattering), per channel",
          "[core][media]" TIER_UNIT) {
  // Chromatic: each channel's distance density differs, so the one-sample MIS over channels is
  // what keeps the weights right.
  const Color sigma_t(0.5f, 1.0f, 2.0f), albedo(0.9f, 0.5f, 0.2f);
  const HomogeneousMedium m(sigma_t, albedo, std::make_unique<IsotropicPhase>());
  const Ray ray{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), kInfinity};
  Sampler sampler(7);
  const float d = 1.3f;
  const Color tr = m.transmittance(ray, d, sampler);
  for (int c = 0; c < 3; ++c) CHECK(tr[c] == Approx(std::exp(-sigma_t[c] * d)).epsilon(1e-6));
  constexpr int n = 400000;
  glm::dvec3 passed(0.0), scattered(0.0), scattered_t(0.0);
  std::vector<double> observed(11, 0.0);  // ten distance cells over [0, d) and the passing
  for (int i = 0; i < n; ++i) {
    // The hero channel at random: one event's estimate is its weight over the mean density.
    const MediumEvent e = m.sample(ray, d, int(sampler.next1d() * 3.0f) % 3, sampler);
    const glm::dvec3 w = glm::dvec3(e.weight) * (3.0 / (double(e.pdf.x) + e.pdf.y + e.pdf.z));
    if (e.scattered) {
      REQUIRE(e.t >= 0.0f);
      REQUIRE(e.t < d);
      scattered += w;
      scattered_t += w * double(e.t);
      observed[size_t(std::min(9, int(e.t / d * 10.0f)))] += 1;
    } else {
      CHECK(e.t == d);
      passed += w;
      observed[10] += 1;
    }
  }
  for (int c = 0; c < 3; ++c) {
    const double s = sigma_t[c], T = std::exp(-s * d);
    INFO("channel " << c);
    CHECK(passed[c] / n == Approx(T).epsilon(0.01));
    CHECK(scattered[c] / n == Approx(albedo[c] * (1.0 - T)).epsilon(0.01));
    // The first moment of the scattering distance: integral of t sigma_s e^(-s t) over [0, d].
    const double moment = albedo[c] * (1.0 - T * (1.0 + s * d)) / s;
    CHECK(scattered_t[c] / n == Approx(moment).epsilon(0.015));
  }
  // The distances' distribution: the mean over channels of each one's exponential.
  std::vector<double> expected(11, 0.0);
  for (int c = 0; c < 3; ++c) {
    const double s = sigma_t[c];
    for (int k = 0; k < 10; ++k)
      expected[size_t(k)] += n / 3.0 * (std::exp(-s * d * k / 10.0) - std::exp(-s * d * (k + 1) / 10.0));
    expected[10] += n / 3.0 * std::exp(-s * d);
  }
  const test::Chi2Result r = test::chi2_test(observed, expected);
  INFO(r.message);
  CHECK(r.accepts(test::sidak_alpha(0.01, 1)));
}

TEST_CASE("media: an extinction of zero in a channel passes that channel, and a medium that scatters nothing "
          "passes every segment with its transmittance",
          "[core][media]" TIER_UNIT) {
  // sigma_t 0 in red: red always passes, its exponential never ends within the segment.
  const HomogeneousMedium m(Color(0.0f, 1.0f, 1.0f), Color(0.5f), std::make_unique<IsotropicPhase>());
  const Ray ray{Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), kInfinity};
  Sampler sampler(3);
  constexpr int n = 200000;
  glm::dvec3 passed(0.0);
  for (int i = 0; i < n; ++i) {
    const MediumEvent e = m.sample(ray, 2.0f, i % 3, sampler);
    if (i % 3 == 0) CHECK_FALSE(e.scattered);
    if (!e.scattered) passed += glm::dvec3(e.weight) * (3.0 / (double(e.pdf.x) + e.pdf.y + e.pdf.z));
  }
  CHECK(passed.x / n == Approx(1.0).epsilon(0.01));
  CHECK(passed.y / n == Approx(std::exp(-2.0)).epsilon(0.01));
  const HomogeneousMedium ink(Color(0.5f, 1.0f, 2.0f), Color(0.0f), std::make_unique<IsotropicPhase>());
  const MediumEvent e = ink.sample(ray, 2.0f, 2, sampler);
  CHECK_FALSE(e.scattered);
  CHECK(e.pdf == Color(1.0f));
  CHECK(e.weight.z == Approx(std::exp(-4.0)));
}

namespace {
// A 4 x 3 x 5 grid of densities in [0, 2) over [-1, 1]^3 (one channel).
VolumeGrid random_grid(uint64_t seed) {
  Rng rng(seed);
  return test::make_grid(4, 3, 5, Vec3(-1.0f), Vec3(1.0f), [&](int, int, int) { return 2.0f * rng.next_float(); });
}
}  // namespace

TEST_CASE("media: a grid volume interpolates its voxels trilinearly within its box and is zero outside it",
          "[core][media]" TIER_UNIT) {
  const VolumeGrid g = random_grid(5);
  const GridVolume v(g);
  auto at = [&](int x, int y, int z) { return g.values[size_t((z * g.ny + y) * g.nx + x)]; };
  auto corner = [&](int x, int y, int z) {
    return Vec3(-1.0f + 2.0f * float(x) / float(g.nx - 1), -1.0f + 2.0f * float(y) / float(g.ny - 1),
                -1.0f + 2.0f * float(z) / float(g.nz - 1));
  };
  CHECK(v.eval(corner(0, 0, 0)).x == Approx(at(0, 0, 0)));
  CHECK(v.eval(corner(3, 2, 4)).x == Approx(at(3, 2, 4)));
  CHECK(v.eval(corner(2, 1, 3)).x == Approx(at(2, 1, 3)));
  // Half way between two voxels along y, a third of the way along x.
  const Vec3 p = corner(1, 0, 2) + Vec3((2.0f / 3.0f) / 3.0f, 0.5f, 0.0f);
  const float lerp_x0 = at(1, 0, 2) + (at(2, 0, 2) - at(1, 0, 2)) / 3.0f;
  const float lerp_x1 = at(1, 1, 2) + (at(2, 1, 2) - at(1, 1, 2)) / 3.0f;
  CHECK(v.eval(p).x == Approx(0.5f * (lerp_x0 + lerp_x1)).epsilon(1e-5));
  CHECK(v.eval(Vec3(1.01f, 0.0f, 0.0f)).x == 0.0f);
  float most = 0;
  for (float x : g.values) most = std::max(most, x);
  CHECK(v.max_value() == most);
}

TEST_CASE("media: in a grid medium, ratio tracking's transmittance and delta tracking's chance of passing both "
          "average to exp(-integral of sigma_t), and a constant grid is the homogeneous medium",
          "[core][media]" TIER_UNIT) {
  const VolumeGrid g = random_grid(11);
  const float scale = 0.8f;
  auto medium = [&](VolumeGrid grid) {
    return HeterogeneousMedium(std::make_unique<GridVolume>(std::move(grid)), std::make_unique<ConstVolume>(Color(0.6f)),
                               scale, std::make_unique<IsotropicPhase>());
  };
  const HeterogeneousMedium m = medium(g);
  const GridVolume density(g);
  // A ray entering the box from outside and leaving it before tmax; and one ending inside.
  for (const float tmax : {5.0f, 1.7f}) {
    INFO("tmax " << tmax);
    const Ray ray{Vec3(-1.5f, -0.3f, 0.2f), glm::normalize(Vec3(1.0f, 0.2f, -0.1f)), kInfinity};
    double optical = 0;
    constexpr int steps = 200000;
    for (int i = 0; i < steps; ++i) optical += density.eval(ray.at((i + 0.5f) * tmax / steps)).x * scale * tmax / steps;
    const double expected = std::exp(-optical);
    Sampler sampler(21);
    constexpr int n = 200000;
    double ratio = 0, passed = 0, scattered_weight = 0;
    for (int i = 0; i < n; ++i) {
      ratio += m.transmittance(ray, tmax, sampler).x;
      const MediumEvent e = m.sample(ray, tmax, 0, sampler);
      if (e.scattered) {
        REQUIRE(e.t < tmax);
        scattered_weight += e.weight.x;
      } else {
        passed += 1;
      }
    }
    INFO("optical depth " << optical);
    CHECK(ratio / n == Approx(expected).epsilon(0.01));
    CHECK(passed / n == Approx(expected).epsilon(0.01));
    CHECK(scattered_weight / n == Approx(0.6 * (1.0 - expected)).epsilon(0.01));
  }
  // All voxels 1.25 (times 0.8: sigma_t 1): the homogeneous medium's transmittance.
  VolumeGrid flat = g;
  for (float& x : flat.values) x = 1.25f;
  const HeterogeneousMedium c = medium(flat);
  const Ray ray{Vec3(0.0f, 0.0f, -3.0f), Vec3(0.0f, 0.0f, 1.0f), kInfinity};
  Sampler sampler(4);
  double tr = 0;
  for (int i = 0; i < 100000; ++i) tr += c.transmittance(ray, 10.0f, sampler).x;
  CHECK(tr / 100000 == Approx(std::exp(-2.0)).epsilon(0.01));
}

TEST_CASE("media: a grid placed as Mitsuba 3 places it: the unit cube under to_world, values at the cells' "
          "centres, held beyond the outer centres and clamped outside the box within its bounds; nearest filtering",
          "[core][media]" TIER_UNIT) {
  const VolumeGrid g = random_grid(17);
  auto at = [&](int x, int y, int z) { return g.values[size_t((z * g.ny + y) * g.nx + x)]; };
  GridPlacement place;
  // Scale, then turn 45 degrees about z, then move (Mitsuba's <scale/><rotate/><translate/>).
  place.to_world = glm::translate(glm::mat4(1.0f), Vec3(1.0f, 2.0f, 3.0f)) *
                   glm::rotate(glm::mat4(1.0f), glm::radians(45.0f), Vec3(0.0f, 0.0f, 1.0f)) *
                   glm::scale(glm::mat4(1.0f), Vec3(2.0f, 1.0f, 3.0f));
  place.unit_box = true;
  place.cell_centres = true;
  const GridVolume v(g, place);
  // A point given in the unit cube's coordinates.
  auto world = [&](float u, float w, float t) { return Vec3(place.to_world * glm::vec4(u, w, t, 1.0f)); };
  auto centre = [&](float i, float j, float k) {
    return world((i + 0.5f) / float(g.nx), (j + 0.5f) / float(g.ny), (k + 0.5f) / float(g.nz));
  };
  CHECK(v.eval(centre(0, 0, 0)).x == Approx(at(0, 0, 0)).epsilon(1e-4));
  CHECK(v.eval(centre(3, 2, 4)).x == Approx(at(3, 2, 4)).epsilon(1e-4));
  CHECK(v.eval(centre(2, 1, 3)).x == Approx(at(2, 1, 3)).epsilon(1e-4));
  // Half way between two centres along x.
  CHECK(v.eval(centre(1.5f, 1, 2)).x == Approx(0.5f * (at(1, 1, 2) + at(2, 1, 2))).epsilon(1e-4));
  // Between the box's face and the outer centre, and outside the box (clamped to it): the
  // outer voxel's value.
  CHECK(v.eval(centre(-0.3f, 1, 2)).x == Approx(at(0, 1, 2)).epsilon(1e-4));
  CHECK(v.eval(centre(-1.0f, 1, 2)).x == Approx(at(0, 1, 2)).epsilon(1e-4));
  CHECK(v.eval(centre(3.4f, 2, 4)).x == Approx(at(3, 2, 4)).epsilon(1e-4));
  // The bounds: the rotated box's corners, exactly enclosed.
  const Bounds b = v.bounds();
  Bounds expected;
  for (int i = 0; i < 8; ++i) expected.extend(world(float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)));
  for (int a = 0; a < 3; ++a) {
    CHECK(b.lo[a] == Approx(expected.lo[a]).margin(1e-5));
    CHECK(b.hi[a] == Approx(expected.hi[a]).margin(1e-5));
  }
  // The turned box's bounds: 2 cos 45 + 1 sin 45 wide in x.
  CHECK(b.extent().x == Approx(3.0f / std::sqrt(2.0f)).epsilon(1e-5));
  // Nearest: a point near a centre takes that voxel's value, not a blend.
  place.nearest = true;
  const GridVolume n(g, place);
  CHECK(n.eval(centre(1.3f, 0.8f, 2.2f)).x == Approx(at(1, 1, 2)).epsilon(1e-6));
  CHECK(n.eval(centre(1.7f, 1.2f, 1.6f)).x == Approx(at(2, 1, 2)).epsilon(1e-6));
  // The file's box instead of the unit cube (use_grid_bbox): voxel centres inside [-1, 1]^3.
  place.nearest = false;
  place.unit_box = false;
  place.to_world = glm::mat4(1.0f);
  const GridVolume f(g, place);
  CHECK(f.eval(Vec3(-1.0f + 2.0f * 0.5f / 4.0f, -1.0f + 2.0f * 1.5f / 3.0f, -1.0f + 2.0f * 2.5f / 5.0f)).x ==
        Approx(at(0, 1, 2)).epsilon(1e-4));
}

namespace {
// Three channels of density over random_grid's box, each varying differently: lo + range * a
// uniform number per channel and point.
VolumeGrid chromatic_grid(uint64_t seed, const Color& lo, const Color& range) {
  VolumeGrid g = random_grid(seed);
  g.channels = 3;
  g.values.clear();
  Rng rng(seed);
  for (int i = 0; i < g.nx * g.ny * g.nz; ++i)
    for (int c = 0; c < 3; ++c) g.values.push_back(lo[c] + range[c] * rng.next_float());
  return g;
}
}  // namespace

TEST_CASE("media: a chromatic grid medium tracked in one hero channel gives every channel its transmittance and "
          "its scattered part (spectral MIS over the path), and ratio tracking each channel's transmittance",
          "[core][media]" TIER_UNIT) {
  const VolumeGrid g = chromatic_grid(29, Color(0.2f, 1.0f, 0.0f), Color(0.5f, 1.0f, 3.0f));
  const Color albedo(0.9f, 0.6f, 0.3f);
  const HeterogeneousMedium m(std::make_unique<GridVolume>(g), std::make_unique<ConstVolume>(albedo), 1.0f,
                              std::make_unique<IsotropicPhase>());
  const GridVolume density(g);
  const Ray ray{Vec3(-1.5f, -0.3f, 0.2f), glm::normalize(Vec3(1.0f, 0.2f, -0.1f)), kInfinity};
  const float tmax = 5.0f;
  glm::dvec3 optical(0.0);
  constexpr int steps = 200000;
  for (int i = 0; i < steps; ++i) optical += glm::dvec3(density.eval(ray.at((i + 0.5f) * tmax / steps))) * double(tmax / steps);
  Sampler sampler(31);
  constexpr int n = 300000;
  glm::dvec3 ratio(0.0), passed(0.0), scattered(0.0);
  for (int i = 0; i < n; ++i) {
    ratio += glm::dvec3(m.transmittance(ray, tmax, sampler));
    const MediumEvent e = m.sample(ray, tmax, int(sampler.next1d() * 3.0f) % 3, sampler);
    const glm::dvec3 w = glm::dvec3(e.weight) * (3.0 / (double(e.pdf.x) + e.pdf.y + e.pdf.z));
    (e.scattered ? scattered : passed) += w;
  }
  for (int c = 0; c < 3; ++c) {
    const double T = std::exp(-optical[c]);
    INFO("channel " << c << ", optical depth " << optical[c]);
    CHECK(ratio[c] / n == Approx(T).epsilon(0.01));
    CHECK(passed[c] / n == Approx(T).epsilon(0.015));
    CHECK(scattered[c] / n == Approx(albedo[c] * (1.0 - T)).epsilon(0.015));
  }
  // The channels differ enough that one tracked alone would get the others wrong.
  CHECK(std::exp(-optical[2]) < 0.5 * std::exp(-optical[0]));
}

TEST_CASE("media: a chromatic flight's record of null collisions gives every channel its transmittance to each "
          "point before the flight's end, whichever channel was tracked (the beam estimate's weights)",
          "[core][media]" TIER_UNIT) {
  const VolumeGrid g = chromatic_grid(41, Color(0.1f, 0.8f, 0.0f), Color(0.4f, 1.0f, 2.5f));
  const HeterogeneousMedium m(std::make_unique<GridVolume>(g), std::make_unique<ConstVolume>(Color(0.8f)), 1.0f,
                              std::make_unique<IsotropicPhase>());
  const GridVolume density(g);
  const Ray ray{Vec3(-1.5f, 0.3f, -0.2f), glm::normalize(Vec3(1.0f, -0.15f, 0.1f)), kInfinity};
  const float tmax = 5.0f;
  const float points[] = {0.9f, 1.4f, 2.0f, 2.6f, 3.2f};
  // Each point's optical depth per channel, by the midpoint rule.
  std::vector<glm::dvec3> optical;
  for (const float s : points) {
    glm::dvec3 o(0.0);
    constexpr int steps = 100000;
    for (int i = 0; i < steps; ++i) o += glm::dvec3(density.eval(ray.at((i + 0.5f) * s / steps))) * double(s / steps);
    optical.push_back(o);
  }
  FlightRecord record;
  Sampler sampler(43);
  constexpr int n = 400000;
  std::vector<glm::dvec3> sum(std::size(points), glm::dvec3(0.0));
  std::vector<glm::dvec3> survived(std::size(points), glm::dvec3(0.0));
  glm::dvec3 heroes(0.0);
  for (int i = 0; i < n; ++i) {
    const int hero = std::min(int(sampler.next1d() * 3.0f), 2);
    heroes[hero] += 1.0;
    const MediumEvent e = m.sample(ray, tmax, hero, sampler, &record);
    REQUIRE(std::is_sorted(record.t.begin(), record.t.end()));
    const float end = e.scattered ? e.t : tmax;
    for (size_t k = 0; k < std::size(points); ++k) {
      if (points[k] >= end) continue;
      const Color w = record.at(points[k]);
      REQUIRE(max_component(w) <= 3.0f + 1e-4f);  // (the balance heuristic's bound)
      sum[k] += glm::dvec3(w);
      survived[k][hero] += 1.0;
    }
  }
  for (size_t k = 0; k < std::size(points); ++k) {
    INFO("point " << points[k]);
    for (int c = 0; c < 3; ++c) {
      INFO("channel " << c << ", optical depth " << optical[k][c]);
      CHECK(sum[k][c] / n == Approx(std::exp(-optical[k][c])).epsilon(0.015));
      // Survival alone is the tracked channel's transmittance.
      CHECK(survived[k][c] / heroes[c] == Approx(std::exp(-optical[k][c])).epsilon(0.02));
    }
  }
  // The channels differ enough that survival alone would get the others wrong.
  CHECK(std::exp(-optical[4][2]) < 0.5 * std::exp(-optical[4][0]));
  // A grey extinction records nothing (every channel's weight is survival's).
  const HeterogeneousMedium grey(std::make_unique<GridVolume>(random_grid(37)), std::make_unique<ConstVolume>(Color(0.8f)),
                                 1.0f, std::make_unique<IsotropicPhase>());
  for (int i = 0; i < 100; ++i) {
    grey.sample(ray, tmax, i % 3, sampler, &record);
    REQUIRE(record.t.empty());
  }
}

TEST_CASE("media: a path's hero throughput stays finite and exact over hundreds of thin-medium events",
          "[core][media]" TIER_UNIT) {
  // Scattering events in a thin grey fog (sigma_t 0.003, albedo 0.9, 100 units apart): each
  // event's weight sigma_s Tr and density sigma_t Tr are ~1e-3, their products underflow a
  // float within 15 events; the throughput, albedo^n, must not.
  const float sigma_t = 0.003f, albedo = 0.9f;
  MediumEvent e;
  e.scattered = true;
  const float tr = std::exp(-sigma_t * 100.0f);
  e.weight = Color(albedo * sigma_t * tr);
  e.pdf = Color(sigma_t * tr);
  Color beta(1.0f), r(1.0f);
  for (int n = 1; n <= 300; ++n) {
    REQUIRE(take_medium_event(e, n % 3, beta, r));
    const Color t = hero_throughput(beta, r);
    INFO("event " << n);
    REQUIRE(t.x == Approx(std::pow(double(albedo), n)).epsilon(1e-3));
  }
  // A chromatic event: the hero channel's density alone scales, the mean of r weighs them.
  Color b2(1.0f), r2(1.0f);
  MediumEvent c;
  c.weight = Color(0.2f, 0.4f, 0.8f);
  c.pdf = Color(0.5f, 1.0f, 2.0f);
  REQUIRE(take_medium_event(c, 1, b2, r2));
  const Color t = hero_throughput(b2, r2);
  for (int ch = 0; ch < 3; ++ch) CHECK(t[ch] == Approx(c.weight[ch] * 3.0 / 3.5));
  // No density in the hero channel ends the path.
  c.pdf = Color(0.5f, 0.0f, 2.0f);
  CHECK_FALSE(take_medium_event(c, 1, b2, r2));
}
