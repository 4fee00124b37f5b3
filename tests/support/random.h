// Random points and sample pairs for tests.
#pragma once
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

}  // namespace caustica::test
