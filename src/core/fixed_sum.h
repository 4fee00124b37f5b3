// Order-independent sums of floats. Each value is rounded once, on its own, to a multiple of
// 2^-64 held in a 128-bit integer; integer addition is associative, so a sum is the same bit
// for bit however its terms are grouped: by pass, by tile, or across MPI ranks.
//
// Range: values are clamped to +-1e12 and a sum may reach about 9.2e18 (2^63), so a pixel holds
// over a million samples at the clamp. Resolution: values below 2^-64 (5.4e-20) vanish, and a
// float's bits below 2^-64 are dropped, so floats from 2^-41 (4.5e-13) up are held exactly.
#pragma once
#include <algorithm>
#include <cmath>

namespace caustica {

using FixedSum = __int128;

constexpr int kFixedFractionBits = 64;
constexpr double kFixedMaxValue = 1e12;

// The fixed-point value of v (NaN counts as 0), rounded toward zero.
inline FixedSum to_fixed(double v) {
  if (!(v == v)) return 0;
  v = std::clamp(v, -kFixedMaxValue, kFixedMaxValue);
  return FixedSum(std::ldexp(v, kFixedFractionBits));
}

// The double nearest a fixed-point sum.
inline double from_fixed(FixedSum s) { return std::ldexp(double(s), -kFixedFractionBits); }

}  // namespace caustica
