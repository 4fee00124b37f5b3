// Per-sample random stream plus a counter of rays traced (for statistics).
#pragma once
#include "core/math.h"
#include "core/rng.h"

namespace caustica {

struct Sampler {
  Rng rng;
  uint64_t rays = 0;
  // Extra per-sample outputs (AOVs) an integrator may fill: kAovCount floats, or null.
  // The photon integrators write [global photons, caustic photons, global radius, caustic radius].
  static constexpr int kAovCount = 4;
  float* aov = nullptr;
  // The image pixel (y * width + x) this sample belongs to, for integrators that keep per-pixel
  // state (SPPM); in a progressive render each pixel is visited by one thread per pass.
  uint64_t pixel = 0;
  // The pixel filter's weight of this sample (1 unless the filter has negative lobes): the
  // render loop scales Li by it; integrators that add to per-pixel state scale that too.
  float filter_weight = 1.0f;
  Sampler() = default;
  explicit Sampler(uint64_t seed) : rng(seed) {}
  float next1d() { return rng.next_float(); }
  Vec2 next2d() {
    const float a = rng.next_float();
    return Vec2(a, rng.next_float());
  }
};

}  // namespace caustica
