// Stratified sample values for one pixel sample (pbrt-v4's padded Sobol' sampler, Cycles' Sobol-Burley).
//
// Every request for a value is a "dimension". For each dimension the spp samples of one pixel draw from the same
// randomised (0,2)-sequence (Sobol' dimensions 0 and 1): the sample index is shuffled and the point Owen-scrambled
// with seeds hashed from (seed, pixel, dimension) (Burley 2020, "Practical hash-based Owen scrambling"). So within
// a pixel the samples of each 2D request cover the unit square evenly (the first 2^m of them form a (0,m,2)-net),
// while different pixels and different dimensions are independent, and every single value is uniform on [0, 1):
// the estimator is unchanged, only its variance drops. Integrators place their requests at fixed dimensions
// (set_dimension) so that, e.g., the first bounce direction of every sample of a pixel is stratified together.
// Past kStratifiedDimensions the values come from an independent PCG stream: deep bounces gain nothing from
// stratification and the hashing would only cost time.
//
// Values depend only on (seed, pixel, absolute sample index, dimension): images are bit-identical for any thread
// count, tile order and spp split.
#pragma once
#include <array>
#include <cstdint>

#include "core/math.h"
#include "core/rng.h"
#include "core/vec.h"

namespace kiln {

inline constexpr uint32_t kStratifiedDimensions = 64;

inline constexpr uint32_t reverse_bits(uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  return __builtin_bswap32(v);
}

// Laine-Karras permutation: each bit is flipped depending on the seed and on the less significant bits only. On
// bit-reversed values that is an Owen scramble (a bit depends on the more significant digits).
inline constexpr uint32_t laine_karras(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Owen scrambling of the digits of v (most significant first), as a hash.
inline constexpr uint32_t owen_scramble(uint32_t v, uint32_t seed) {
  return reverse_bits(laine_karras(reverse_bits(v), seed));
}

// Sobol' dimension 1 (dimension 0 is reverse_bits): together they form the (0,2)-sequence. Generator matrix
// columns are the rows of Pascal's triangle mod 2, built here incrementally (v ^= v >> 1).
inline constexpr uint32_t sobol_dimension1(uint32_t i) {
  uint32_t r = 0;
  for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
    if (i & 1u) r ^= v;
  return r;
}

// Sobol' dimension 1 of a 16-bit index, bit-reversed, from two byte tables (the map is linear over GF(2)). 16 index
// bits give every pixel up to 65536 distinct points; the output scramble fills the finer digits at random.
inline constexpr auto kReversedSobol1Low = [] {
  std::array<uint32_t, 256> t{};
  for (uint32_t b = 0; b < 256; ++b) t[b] = reverse_bits(sobol_dimension1(b));
  return t;
}();
inline constexpr auto kReversedSobol1High = [] {
  std::array<uint32_t, 256> t{};
  for (uint32_t b = 0; b < 256; ++b) t[b] = reverse_bits(sobol_dimension1(b << 8));
  return t;
}();
inline uint32_t reversed_sobol_dimension1(uint32_t i) {
  return kReversedSobol1Low[i & 0xffu] ^ kReversedSobol1High[(i >> 8) & 0xffu];
}

inline float unit_float(uint32_t bits) {
  const float f = float(bits >> 8) * 0x1p-24f;
  return f < kOneMinusEpsilon ? f : kOneMinusEpsilon;
}

class Sampler {
  // Keeps dedicated streams apart from the numbered dimensions' hashes.
  static constexpr uint64_t kDedicatedStreamKey = 0x9e3779b97f4a7c15ull;

 public:
  Sampler(uint64_t seed, uint32_t px, uint32_t py, uint64_t sample_index)
      : key_(mix64(seed ^ mix64((uint64_t(py) << 32) | px))),
        reversed_index_(reverse_bits(uint32_t(sample_index))),
        rng_(mix64(seed ^ mix64(sample_index)), mix64(((uint64_t(py) << 32) | px) ^ mix64(seed + 0x51ed27))) {}

  // The next request draws dimension d (requests then continue at d + 1).
  void set_dimension(uint32_t d) { dim_ = d; }
  uint32_t dimension() const { return dim_; }

  // Written in the bit-reversed domain, where an Owen scramble is one Laine-Karras permutation: the shuffled
  // index is i' = reverse(LK(reverse(i))), and a point p is scrambled as reverse(LK(reverse(p))), with
  // reverse(p) = i' for Sobol' dimension 0 and the reversed table value for dimension 1.
  float next_float() {
    if (dim_ >= kStratifiedDimensions) return rng_.next_float();
    const uint64_t h = mix64(key_ ^ (uint64_t(dim_++) << 1));
    const uint32_t shuffled = reverse_bits(laine_karras(reversed_index_, uint32_t(h)));
    return unit_float(reverse_bits(laine_karras(shuffled, uint32_t(h >> 32))));
  }
  // A value of a dedicated stream outside the dimension sequence (e.g. the shutter time): stratified over the
  // pixel's samples like a dimension, but reading it neither advances the dimension nor draws from the independent
  // tail, so a renderer that asks for it leaves every other value (and the image of a scene that never asks) as is.
  float dedicated_1d(uint32_t stream) const {
    const uint64_t h = mix64(key_ ^ (uint64_t(stream) << 1) ^ kDedicatedStreamKey);
    const uint32_t shuffled = reverse_bits(laine_karras(reversed_index_, uint32_t(h)));
    return unit_float(reverse_bits(laine_karras(shuffled, uint32_t(h >> 32))));
  }
  // Passes over one 1D request without computing it: the value would be thrown away (a single-lobe BSDF's lobe
  // choice). Every later request gets the value it would have had.
  void skip_1d() {
    if (dim_ >= kStratifiedDimensions) (void)rng_.next_u32();
    else ++dim_;
  }
  // next_float() when the caller will read it, else skip_1d() and 0.
  float next_float_if(bool read) {
    if (read) return next_float();
    skip_1d();
    return 0.0f;
  }
  Vec2f next_2d() {
    if (dim_ >= kStratifiedDimensions) return rng_.next_2d();
    const uint64_t h = mix64(key_ ^ ((uint64_t(dim_++) << 1) | 1u));
    const uint32_t h2 = uint32_t(mix64(h));
    // Shuffling the index by an Owen scramble keeps its low m bits a permutation of 0..2^m-1, and the first m
    // digits of a Sobol' point depend only on those bits: the pixel's first 2^m samples stay a (0,m,2)-net.
    const uint32_t shuffled = reverse_bits(laine_karras(reversed_index_, uint32_t(h)));
    return {unit_float(reverse_bits(laine_karras(shuffled, uint32_t(h >> 32)))),
            unit_float(reverse_bits(laine_karras(reversed_sobol_dimension1(shuffled), h2)))};
  }

 private:
  uint64_t key_;
  uint32_t reversed_index_;
  uint32_t dim_ = 0;
  Rng rng_;
};

}  // namespace kiln
