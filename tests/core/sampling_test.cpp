// Chi-square tests of the warping functions, Distribution1D and Lambertian sampling against
// their densities, plus checks of the chi-square helper itself (it must be able to reject).
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <functional>
#include "core/bsdf/diffuse.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "support/chi2.h"

using namespace caustica;
using caustica::test::Chi2Result;
using caustica::test::Histogram2D;
using caustica::test::SphereHistogram;

namespace {
constexpr int kSamples = 1000000;
// Chi-square tests in this file that are expected to accept; Sidak keeps 0.01 overall.
constexpr int kChi2Tests = 10;
const double kAlpha = test::sidak_alpha(0.01, kChi2Tests);

Vec2 next2(Rng& rng) {
  const float a = rng.next_float();
  return Vec2(a, rng.next_float());
}

// Fills a sphere histogram with kSamples directions and tests them against pdf; also checks
// that the pdf integrates to one and that every direction is unit length.
Chi2Result sphere_chi2(const std::function<Vec3(Rng&)>& sample, const std::function<double(const Vec3&)>& pdf,
                       int n_cos, int n_phi, uint64_t seed) {
  Rng rng(seed);
  SphereHistogram hist(n_cos, n_phi);
  int not_unit = 0;
  for (int i = 0; i < kSamples; ++i) {
    const Vec3 w = sample(rng);
    if (!(std::abs(glm::length(w) - 1.0f) < 1e-5f)) ++not_unit;
    hist.add(w);
  }
  CHECK(not_unit == 0);
  const std::vector<double> expected = hist.expected(pdf, kSamples);
  CHECK(test::sum(expected) / kSamples == Approx(1.0).margin(1e-3));  // the pdf integrates to 1
  return test::chi2_test(hist.counts(), expected);
}
}  // namespace

TEST_CASE("chi2 helper: incomplete gamma and p-values match tables", "[core][sampling][chi2]" TIER_UNIT) {
  for (double x : {0.01, 0.5, 1.0, 3.0, 10.0, 40.0}) CHECK(test::gamma_q(1.0, x) == Approx(std::exp(-x)).epsilon(1e-12));
  // Q(1/2, x) = erfc(sqrt(x)).
  for (double x : {0.01, 0.3, 1.2, 5.0, 20.0}) CHECK(test::gamma_q(0.5, x) == Approx(std::erfc(std::sqrt(x))).epsilon(1e-10));
  // Upper 1% points of the chi-square distribution (Abramowitz & Stegun table 26.8).
  CHECK(test::chi2_p_value(6.634897, 1) == Approx(0.01).epsilon(1e-5));
  CHECK(test::chi2_p_value(23.209251, 10) == Approx(0.01).epsilon(1e-5));
  CHECK(test::chi2_p_value(135.806723, 100) == Approx(0.01).epsilon(1e-5));
  CHECK(test::chi2_p_value(199.334, 200) == Approx(0.5).margin(2e-3));  // median ~ k (1 - 2 / 9k)^3
  CHECK(test::chi2_p_value(0.0, 7) == 1.0);
  CHECK(test::sidak_alpha(0.01, 1) == Approx(0.01));
  CHECK(test::sidak_alpha(0.01, 10) == Approx(0.0010045).epsilon(1e-4));
}

TEST_CASE("chi2 helper: pooling, exact fit, zero-expected cells", "[core][sampling][chi2]" TIER_UNIT) {
  const std::vector<double> expected = {1, 1, 1, 2, 100, 100};
  Chi2Result exact = test::chi2_test(expected, expected);
  CHECK(exact.statistic == 0.0);
  CHECK(exact.p_value == Approx(1.0));
  CHECK(exact.pooled_cells == 4);  // 1 + 1 + 1 + 2 = 5 reaches the minimum expected count
  CHECK(exact.dof == 2);           // pooled cell + two large cells, minus one

  Chi2Result off = test::chi2_test({0, 0, 0, 5, 100, 100}, expected);
  CHECK(off.statistic == Approx(0.0));  // pooled 5 against 5
  Chi2Result skewed = test::chi2_test({5, 0, 0, 0, 150, 50}, expected);
  CHECK(skewed.statistic == Approx(50.0));
  CHECK_FALSE(skewed.accepts(kAlpha));

  Chi2Result impossible = test::chi2_test({1, 100, 100}, {0, 100.5, 100.5});
  CHECK(impossible.p_value == 0.0);
}

TEST_CASE("chi2 negative control: cosine samples fail against the uniform hemisphere pdf", "[core][sampling][chi2]" TIER_UNIT) {
  const Chi2Result wrong = sphere_chi2([](Rng& r) { return sample_cosine_hemisphere(next2(r)); },
                                       [](const Vec3& w) { return w.z > 0 ? double(uniform_hemisphere_pdf()) : 0.0; },
                                       40, 80, 1);
  INFO(wrong.message);
  CHECK_FALSE(wrong.accepts(kAlpha));
  CHECK(wrong.p_value < 1e-12);
}

TEST_CASE("chi2 negative control: a 5% tilt of the uniform sphere is detected", "[core][sampling][chi2]" TIER_UNIT) {
  const Chi2Result wrong = sphere_chi2([](Rng& r) { return sample_uniform_sphere(next2(r)); },
                                       [](const Vec3& w) { return (1.0 + 0.05 * w.z) / (4.0 * test::kPi64); }, 40, 80, 2);
  INFO(wrong.message);
  CHECK_FALSE(wrong.accepts(kAlpha));
}

TEST_CASE("sample_cosine_hemisphere follows cos/pi", "[core][sampling]" TIER_UNIT) {
  const Chi2Result r = sphere_chi2([](Rng& rng) { return sample_cosine_hemisphere(next2(rng)); },
                                   [](const Vec3& w) { return double(cosine_hemisphere_pdf(w.z)); }, 40, 80, 11);
  INFO(r.message);
  CHECK(r.accepts(kAlpha));
  CHECK(cosine_hemisphere_pdf(1.0f) == Approx(1.0 / test::kPi64));
  CHECK(cosine_hemisphere_pdf(-0.5f) == 0.0f);
}

TEST_CASE("sample_uniform_sphere is uniform", "[core][sampling]" TIER_UNIT) {
  const Chi2Result r = sphere_chi2([](Rng& rng) { return sample_uniform_sphere(next2(rng)); },
                                   [](const Vec3&) { return double(uniform_sphere_pdf()); }, 40, 80, 12);
  INFO(r.message);
  CHECK(r.accepts(kAlpha));
}

TEST_CASE("sample_uniform_hemisphere is uniform over z > 0", "[core][sampling]" TIER_UNIT) {
  const Chi2Result r = sphere_chi2([](Rng& rng) { return sample_uniform_hemisphere(next2(rng)); },
                                   [](const Vec3& w) { return w.z > 0 ? double(uniform_hemisphere_pdf()) : 0.0; },
                                   40, 80, 13);
  INFO(r.message);
  CHECK(r.accepts(kAlpha));
}

TEST_CASE("sample_uniform_cone is uniform inside the cone", "[core][sampling]" TIER_UNIT) {
  const float cos_max = 0.8f;
  // 100 cells in cos theta put a cell edge at exactly 0.8 and 10 cells inside the cone.
  const Chi2Result r =
      sphere_chi2([&](Rng& rng) { return sample_uniform_cone(next2(rng), cos_max); },
                  [&](const Vec3& w) { return w.z >= cos_max ? double(uniform_cone_pdf(cos_max)) : 0.0; }, 100, 50, 14);
  INFO(r.message);
  CHECK(r.accepts(kAlpha));
  CHECK(uniform_cone_pdf(cos_max) == Approx(1.0 / (2.0 * test::kPi64 * 0.2)));
}

TEST_CASE("sample_concentric_disk is uniform over the unit disc", "[core][sampling]" TIER_UNIT) {
  // Polar cells of equal area: r^2 in [0, 1] times phi in [0, 2 pi), density 1 / (2 pi).
  Rng rng(15);
  Histogram2D hist(0.0, 1.0, 40, 0.0, 2.0 * test::kPi64, 64);
  int outside = 0;
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 p = sample_concentric_disk(next2(rng));
    const double r2 = double(p.x) * p.x + double(p.y) * p.y;
    if (r2 > 1.0 + 1e-6) ++outside;
    double phi = std::atan2(double(p.y), double(p.x));
    if (phi < 0) phi += 2.0 * test::kPi64;
    hist.add(std::min(r2, 1.0), phi);
  }
  CHECK(outside == 0);
  // The density in (r^2, phi) is pdf_area * dA / d(r^2) dphi = (1/pi) * 1/2.
  const std::vector<double> expected = hist.expected([](double, double) { return unit_disk_pdf() * 0.5; }, kSamples);
  CHECK(test::sum(expected) / kSamples == Approx(1.0).margin(1e-3));
  const Chi2Result r = test::chi2_test(hist.counts(), expected);
  INFO(r.message);
  CHECK(r.accepts(kAlpha));
  CHECK(sample_concentric_disk(Vec2(0.5f)) == Vec2(0.0f));
}

TEST_CASE("sample_uniform_triangle is uniform over barycentrics", "[core][sampling]" TIER_UNIT) {
  // Grid over (b0, b1); cells below the diagonal b0 + b1 = 1 are whole, cells on it are cut in half.
  constexpr int n = 25;
  Rng rng(16);
  Histogram2D hist(0.0, 1.0, n, 0.0, 1.0, n);
  int bad = 0;
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 b = sample_uniform_triangle(next2(rng));
    if (!(b.x >= 0 && b.y >= 0 && 1.0f - b.x - b.y >= -1e-6f)) ++bad;
    hist.add(b.x, b.y);
  }
  CHECK(bad == 0);
  std::vector<double> expected(hist.cell_count(), 0.0);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double cell_area = 1.0 / (n * n);
      const double inside = i + j < n - 1 ? cell_area : i + j == n - 1 ? 0.5 * cell_area : 0.0;
      expected[size_t(j) * n + i] = kSamples * 2.0 * inside;  // density 2 over a triangle of area 1/2
    }
  }
  CHECK(test::sum(expected) == Approx(kSamples));
  const Chi2Result r = test::chi2_test(hist.counts(), expected);
  INFO(r.message);
  CHECK(r.accepts(kAlpha));
}

TEST_CASE("Distribution1D samples in proportion to the weights and never a zero weight", "[core][sampling]" TIER_UNIT) {
  const std::vector<float> weights = {0.0f, 1.0f, 3.0f, 0.0f, 0.5f, 2.5f, 7.0f, 0.0f};
  const double total = 14.0;
  Distribution1D dist(weights.data(), weights.size());
  REQUIRE(dist.size() == weights.size());
  CHECK(dist.total() == Approx(total));
  for (size_t i = 0; i < weights.size(); ++i) CHECK(dist.pmf(i) == Approx(weights[i] / total));

  Rng rng(17);
  std::vector<double> counts(weights.size(), 0.0), expected(weights.size());
  Histogram2D remapped(0.0, 1.0, 100, 0.0, 1.0, 1);
  int wrong_pmf = 0;
  for (int k = 0; k < kSamples; ++k) {
    float u = rng.next_float();
    float pmf = -1;
    const size_t i = dist.sample_remap(u, &pmf);
    REQUIRE(i < weights.size());
    counts[i] += 1;
    if (pmf != dist.pmf(i)) ++wrong_pmf;
    remapped.add(u, 0.5);
  }
  CHECK(wrong_pmf == 0);
  for (size_t i = 0; i < weights.size(); ++i) expected[i] = kSamples * weights[i] / total;
  CHECK(counts[0] == 0);
  CHECK(counts[3] == 0);
  CHECK(counts[7] == 0);
  const Chi2Result r = test::chi2_test(counts, expected);
  INFO(r.message);
  CHECK(r.accepts(kAlpha));

  // The remapped number is a fresh uniform number in [0, 1).
  const Chi2Result ru = test::chi2_test(remapped.counts(), remapped.expected([](double, double) { return 1.0; }, kSamples));
  INFO(ru.message);
  CHECK(ru.accepts(kAlpha));

  // Edges: u = 0, u on a cdf step, u just below 1 never select a zero weight.
  for (float u : {0.0f, 1.0f / 14.0f, 4.0f / 14.0f, 4.5f / 14.0f, 7.0f / 14.0f, 0x1.fffffep-1f}) {
    const size_t i = dist.sample(u);
    INFO("u = " << u << " -> " << i);
    CHECK(weights[i] > 0.0f);
  }
  CHECK(dist.sample(0.0f) == 1);
  CHECK(dist.sample(0x1.fffffep-1f) == 6);
}

TEST_CASE("Distribution1D with all weights zero falls back to uniform", "[core][sampling]" TIER_UNIT) {
  const float zeros[3] = {0, 0, 0};
  Distribution1D dist(zeros, 3);
  for (size_t i = 0; i < 3; ++i) CHECK(dist.pmf(i) == Approx(1.0 / 3.0));
  CHECK(dist.sample(0.1f) == 0);
  CHECK(dist.sample(0.5f) == 1);
  CHECK(dist.sample(0.9f) == 2);
}

TEST_CASE("Lambertian::eval is albedo/pi on the same side and 0 across", "[core][sampling][material]" TIER_UNIT) {
  const Color albedo(0.2f, 0.5f, 0.8f);
  const Lambertian lam(albedo);
  Rng rng(18);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 a = sample_uniform_hemisphere(next2(rng)), b = sample_uniform_hemisphere(next2(rng));
    if (a.z <= 0 || b.z <= 0) continue;
    const Vec3 a_below(a.x, a.y, -a.z), b_below(b.x, b.y, -b.z);
    REQUIRE(lam.eval(a, b).g == Approx(0.5 / test::kPi64).epsilon(1e-6));
    REQUIRE(lam.eval(a_below, b_below).b == Approx(0.8 / test::kPi64).epsilon(1e-6));  // two-sided
    REQUIRE(is_black(lam.eval(a, b_below)));
    REQUIRE(is_black(lam.eval(a_below, b)));
    REQUIRE(lam.pdf(a, b) == Approx(b.z / test::kPi64).epsilon(1e-6));
    REQUIRE(lam.pdf(a_below, b_below) == Approx(b.z / test::kPi64).epsilon(1e-6));
    REQUIRE(lam.pdf(a, b_below) == 0.0f);
  }
  CHECK(lam.is_lambertian());
  CHECK_FALSE(lam.is_specular());
  CHECK(lam.albedo() == albedo);
}

TEST_CASE("Lambertian::sample matches Lambertian::pdf on both sides", "[core][sampling][material]" TIER_UNIT) {
  const Color albedo(0.25f, 0.5f, 0.75f);
  const Lambertian lam(albedo);
  const Vec3 up = glm::normalize(Vec3(0.3f, -0.4f, 0.8f));
  for (const Vec3 wo : {up, Vec3(up.x, up.y, -up.z)}) {
    INFO("wo = (" << wo.x << ", " << wo.y << ", " << wo.z << ")");
    int failed = 0, wrong_side = 0, bad_pdf = 0, bad_weight = 0, bad_eval = 0, bad_flags = 0;
    const std::function<Vec3(Rng&)> sample = [&](Rng& rng) {
      BsdfSample s;
      if (!lam.sample(wo, next2(rng), rng.next_float(), s)) {
        ++failed;
        return Vec3(0, 0, wo.z > 0 ? 1 : -1);
      }
      if (!(s.wi.z * wo.z > 0)) ++wrong_side;
      if (!(std::abs(s.pdf - lam.pdf(wo, s.wi)) <= 1e-5f * s.pdf)) ++bad_pdf;
      if (glm::length(s.weight - albedo) > 1e-6f) ++bad_weight;
      // weight = f cos / pdf
      const Color w = lam.eval(wo, s.wi) * std::abs(s.wi.z) / s.pdf;
      if (glm::length(w - albedo) > 1e-4f) ++bad_eval;
      if (s.delta) ++bad_flags;
      return s.wi;
    };
    const Chi2Result r = sphere_chi2(sample, [&](const Vec3& w) { return double(lam.pdf(wo, w)); }, 40, 80,
                                     wo.z > 0 ? 19 : 20);
    INFO(r.message);
    CHECK(r.accepts(kAlpha));
    CHECK(failed < 10);  // only wi.z == 0 exactly may fail
    CHECK(wrong_side == 0);
    CHECK(bad_pdf == 0);
    CHECK(bad_weight == 0);
    CHECK(bad_eval == 0);
    CHECK(bad_flags == 0);
  }
  BsdfSample s;
  CHECK_FALSE(lam.sample(Vec3(1, 0, 0), Vec2(0.3f, 0.7f), 0.5f, s));  // grazing wo has no side
}
