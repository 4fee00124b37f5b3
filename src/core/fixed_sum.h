// Order-independent sums of floats. Each value is rounded once, on its own, to a multiple of
// 2^-64 held in a 128-bit integer; integer addition is associative, so a sum is the same bit
// for bit however its terms are grouped: by pass, by tile, or across MPI ranks.
//
// Range: values are clamped to +-1e12 and a sum may reach about 9.2e18 (2^63), so a pixel holds
// over nine million samples at the clamp (beyond, add_saturating holds the sum at its limit).
// Resolution: values below 2^-64 (5.4e-20) vanish, and a float's bits below 2^-64 are dropped,
// so floats from 2^-41 (4.5e-13) up are held exactly.
#pragma once
#include <algorithm>
#include <cmath>

namespace caustica {

using FixedSum = __int128;

constexpr int kFixedFractionBits = 64;
constexpr double kFixedMaxValue = 1e12;
// 2^64 and 2^-64: scaling by a power of two is exact here, as ldexp is, and a multiplication
// costs less than its library call.
constexpr double kFixedOne = 0x1p64, kFixedUnit = 0x1p-64;
static_assert(kFixedFractionBits == 64, "kFixedOne and kFixedUnit are 2^64 and 2^-64");

// The fixed-point value of v (NaN counts as 0), rounded toward zero.
inline FixedSum to_fixed(double v) {
  if (!(v == v)) return 0;
  v = std::clamp(v, -kFixedMaxValue, kFixedMaxValue);
  return FixedSum(v * kFixedOne);
}

// s += v, held at the largest or smallest FixedSum instead of overflowing (over 9e6 samples at
// the clamp in one sum); short of that, exact.
inline void add_saturating(FixedSum& s, FixedSum v) {
  if (__builtin_add_overflow(s, v, &s)) {
    constexpr FixedSum kMax = FixedSum((static_cast<unsigned __int128>(1) << 127) - 1);
    s = v > 0 ? kMax : -kMax - 1;
  }
}

// The double nearest a fixed-point sum.
inline double from_fixed(FixedSum s) { return double(s) * kFixedUnit; }

}  // namespace caustica
