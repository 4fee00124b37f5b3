// Random points and sample pairs for tests.
#pragma once
#include <string>
#include "core/math.h"
#include "core/rng.h"

namespace caustica::test {

inline Vec2 next2(Rng& rng) {
  const float a = rng.next_float();
  return Vec2(a, rng.next_float());
}

inline Vec3 random_in_box(Rng& rng, float lo, float hi) {
  const float x = rng.next_float(), y = rng.next_float(), z = rng.next_float();
  return Vec3(lo + (hi - lo) * x, lo + (hi - lo) * y, lo + (hi - lo) * z);
}

// A fuzzed copy of a good file: 1 to 4 bytes overwritten at random, then, with probability
// `truncate`, cut at a random length.
inline std::string corrupt(const std::string& good, Rng& rng, float truncate) {
  std::string b = good;
  const int edits = 1 + int(rng.next_float() * 4.0f);
  for (int e = 0; e < edits; ++e) b[size_t(rng.next_float() * float(b.size())) % b.size()] = char(rng.next_u32() & 0xff);
  if (rng.next_float() < truncate) b.resize(size_t(rng.next_float() * float(b.size())));
  return b;
}

}  // namespace caustica::test
