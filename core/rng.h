// Deterministic random numbers. Every pixel sample owns a PCG32 stream seeded from (scene seed, pixel, absolute
// sample index), so the image is bit-identical for any thread count, tile order or spp split.
#pragma once
#include <cstdint>

#include "core/vec.h"

namespace kiln {

inline constexpr uint64_t mix64(uint64_t z) {
  // SplitMix64 finaliser: a bijective avalanche mix.
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

class Rng {
 public:
  Rng() : Rng(0, 0) {}
  Rng(uint64_t seed, uint64_t stream) { seed_stream(seed, stream); }
  void seed_stream(uint64_t seed, uint64_t stream) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }
  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }
  // Uniform in [0, 1).
  float next_float() {
    const float f = float(next_u32() >> 8) * 0x1p-24f;
    return f < kOneMinusEpsilon ? f : kOneMinusEpsilon;
  }
  Vec2f next_2d() {
    const float a = next_float();
    return {a, next_float()};
  }

 private:
  uint64_t state_ = 0, inc_ = 1;
};

// The stream for one pixel sample.
inline Rng pixel_sample_rng(uint64_t seed, uint32_t px, uint32_t py, uint64_t sample_index) {
  const uint64_t pixel = (uint64_t(py) << 32) | px;
  return Rng(mix64(seed ^ mix64(sample_index)), mix64(pixel ^ mix64(seed + 0x51ed27)));
}

}  // namespace kiln
