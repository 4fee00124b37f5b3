// PCG32 random numbers, seeded by hashing (pixel, sample index, seed) or (photon index, seed).
#pragma once
#include <cstdint>

namespace caustica {

// 64-bit finaliser of MurmurHash3: a good avalanche for combining seeds.
inline uint64_t mix64(uint64_t k) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdULL;
  k ^= k >> 33;
  k *= 0xc4ceb9fe1a85ec53ULL;
  k ^= k >> 33;
  return k;
}

inline uint64_t hash_seed(uint64_t a, uint64_t b = 0, uint64_t c = 0) {
  uint64_t h = mix64(a + 0x9e3779b97f4a7c15ULL);
  h = mix64(h ^ (b + 0x632be59bd9b4e019ULL));
  h = mix64(h ^ (c + 0x85ebca77c2b2ae63ULL));
  return h;
}

// O'Neill's PCG32 (XSH RR), period 2^64 per stream.
class Rng {
 public:
  explicit Rng(uint64_t seed = 0, uint64_t stream = 0) { seed_with(seed, stream); }
  void seed_with(uint64_t seed, uint64_t stream = 0) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }
  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }
  // Uniform in [0, 1): 24 random bits, so the result is never rounded up to 1.
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_ = 0, inc_ = 1;
};

}  // namespace caustica
