#include "core/rng.h"

#include <gtest/gtest.h>

#include <array>
#include <set>
#include <tuple>
#include <vector>

#include "support/chi2.h"

namespace kiln {
namespace {

TEST(Rng, DeterministicForSeedAndStream) {
  Rng a(42, 7), b(42, 7);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.next_u32(), b.next_u32());
  Rng c(42, 7);
  c.seed_stream(42, 7);  // reseeding restarts the sequence
  Rng d(42, 7);
  for (int i = 0; i < 10; ++i) ASSERT_EQ(c.next_u32(), d.next_u32());
  // Default construction is a fixed stream too.
  Rng e, f;
  EXPECT_EQ(e.next_u32(), f.next_u32());
}

TEST(Rng, SeedsAndStreamsGiveDifferentSequences) {
  auto first8 = [](Rng r) {
    std::array<uint32_t, 8> v{};
    for (uint32_t& x : v) x = r.next_u32();
    return v;
  };
  const auto base = first8(Rng(1, 1));
  EXPECT_NE(base, first8(Rng(2, 1)));
  EXPECT_NE(base, first8(Rng(1, 2)));
  EXPECT_NE(first8(Rng(0, 0)), first8(Rng(0, 1)));
}

TEST(Rng, NextFloatInHalfOpenUnitInterval) {
  Rng rng(3, 0);
  float lo = 1.0f, hi = 0.0f;
  for (int i = 0; i < 1'000'000; ++i) {
    const float u = rng.next_float();
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  EXPECT_GE(lo, 0.0f);
  EXPECT_LT(hi, 1.0f);
  EXPECT_LT(lo, 1e-4f);
  EXPECT_GT(hi, 1.0f - 1e-4f);
  EXPECT_LT(kOneMinusEpsilon, 1.0f);
  EXPECT_EQ(std::nextafter(kOneMinusEpsilon, 2.0f), 1.0f);
}

TEST(Rng, NextFloatIsUniform) {
  constexpr int kBins = 256;
  std::vector<uint64_t> obs(kBins, 0);
  Rng rng(4, 0);
  for (int i = 0; i < 1'000'000; ++i) ++obs[size_t(rng.next_float() * kBins)];
  const std::vector<double> p(kBins, 1.0 / kBins);
  const auto r = test::chi2_discrete(obs, p);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Rng, Next2dDrawsTwoConsecutiveFloats) {
  Rng a(5, 5), b(5, 5);
  const Vec2f u = a.next_2d();
  const float x = b.next_float();
  EXPECT_EQ(u.x, x);
  EXPECT_EQ(u.y, b.next_float());
  // Successive pairs are uniform on the unit square (no correlation between the two coordinates).
  constexpr int kBins = 16;
  std::vector<uint64_t> obs(kBins * kBins, 0);
  for (int i = 0; i < 1'000'000; ++i) {
    const Vec2f v = a.next_2d();
    ++obs[size_t(int(v.x * kBins) * kBins + int(v.y * kBins))];
  }
  const std::vector<double> p(obs.size(), 1.0 / double(obs.size()));
  const auto r = test::chi2_discrete(obs, p);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(PixelSampleRng, StreamsDifferAcrossPixelsSamplesAndSeeds) {
  // The first four outputs of every (seed, pixel, sample) stream in a block are distinct.
  std::set<std::array<uint32_t, 4>> seen;
  int total = 0;
  for (uint64_t seed : {0ull, 1ull})
    for (uint32_t y = 0; y < 32; ++y)
      for (uint32_t x = 0; x < 32; ++x)
        for (uint64_t s = 0; s < 8; ++s) {
          Rng r = pixel_sample_rng(seed, x, y, s);
          seen.insert({r.next_u32(), r.next_u32(), r.next_u32(), r.next_u32()});
          ++total;
        }
  EXPECT_EQ(int(seen.size()), total);
  // x and y are not interchangeable.
  EXPECT_NE(pixel_sample_rng(0, 1, 2, 0).next_u32(), pixel_sample_rng(0, 2, 1, 0).next_u32());
  // The same pixel sample always gets the same stream (render determinism).
  Rng a = pixel_sample_rng(9, 100, 200, 300), b = pixel_sample_rng(9, 100, 200, 300);
  for (int i = 0; i < 100; ++i) ASSERT_EQ(a.next_u32(), b.next_u32());
}

TEST(PixelSampleRng, FirstDrawsAreUniformAcrossPixels) {
  // Seeding from structured pixel coordinates must not leave structure in the first (most used) dimensions.
  constexpr int kBins = 16;
  std::vector<uint64_t> obs1(kBins * kBins, 0);
  for (uint32_t y = 0; y < 256; ++y)
    for (uint32_t x = 0; x < 256; ++x)
      for (uint64_t s = 0; s < 4; ++s) {
        Rng r = pixel_sample_rng(7, x, y, s);
        const Vec2f u = r.next_2d();
        ++obs1[size_t(int(u.x * kBins) * kBins + int(u.y * kBins))];
      }
  const std::vector<double> p(obs1.size(), 1.0 / double(obs1.size()));
  const auto r = test::chi2_discrete(obs1, p);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Mix64, IsInjectiveOnASample) {
  std::set<uint64_t> seen;
  for (uint64_t i = 0; i < 100000; ++i) seen.insert(mix64(i));
  EXPECT_EQ(seen.size(), 100000u);
  EXPECT_NE(mix64(0), 0u);
}

}  // namespace
}  // namespace kiln
