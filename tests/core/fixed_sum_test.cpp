// Exact, order-independent sums (core/fixed_sum.h): what lets MPI ranks add their images.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>
#include "core/fixed_sum.h"

using namespace caustica;

TEST_CASE("fixed sum: any order and grouping of the same floats gives the same bits", "[core][fixed_sum]" TIER_UNIT) {
  std::mt19937 rng(42);
  // Radiance-like samples over 12 orders of magnitude, with fireflies.
  std::uniform_real_distribution<double> exponent(-8.0, 4.0);
  std::vector<float> v(20000);
  for (float& x : v) x = float(std::pow(10.0, exponent(rng)));
  FixedSum in_order = 0;
  for (float x : v) in_order += to_fixed(x);
  // Shuffled, and split into 7 interleaved parts (as passes among ranks) summed apart.
  std::shuffle(v.begin(), v.end(), rng);
  FixedSum parts[7] = {};
  for (size_t i = 0; i < v.size(); ++i) parts[i % 7] += to_fixed(v[i]);
  FixedSum grouped = 0;
  for (int p = 6; p >= 0; --p) grouped += parts[p];
  CHECK(grouped == in_order);
  // The same floats summed in double in two orders differ: the reason for fixed point.
  double a = 0, b = 0;
  for (float x : v) a += x;
  for (auto it = v.rbegin(); it != v.rend(); ++it) b += *it;
  CHECK(a != b);
  // And the fixed sum is as accurate as a long double sum.
  long double exact = 0;
  for (float x : v) exact += x;
  CHECK(std::abs(from_fixed(in_order) - double(exact)) <= 1e-15 * double(exact));
}

TEST_CASE("fixed sum: values are held exactly down to 2^-41, clamped at 1e12, and NaN counts as 0",
          "[core][fixed_sum]" TIER_UNIT) {
  for (float x : {1.0f, 0.1f, 3.0e-7f, 123456.78f, std::ldexp(1.0f, -41), std::ldexp(1.5f, -30)}) {
    CHECK(from_fixed(to_fixed(x)) == double(x));
    CHECK(from_fixed(to_fixed(-x)) == -double(x));
  }
  // Below 2^-64 a value vanishes; between, its bits below 2^-64 are dropped.
  CHECK(to_fixed(std::ldexp(1.0, -65)) == 0);
  CHECK(from_fixed(to_fixed(std::ldexp(1.0, -64))) == std::ldexp(1.0, -64));
  CHECK(from_fixed(to_fixed(1e30)) == kFixedMaxValue);
  CHECK(from_fixed(to_fixed(-1e30)) == -kFixedMaxValue);
  CHECK(to_fixed(std::numeric_limits<double>::quiet_NaN()) == 0);
  // A million samples at the clamp still fit.
  FixedSum s = 0;
  for (int i = 0; i < 1000000; ++i) s += to_fixed(1e12);
  CHECK(from_fixed(s) == Approx(1e18).epsilon(1e-15));
}
