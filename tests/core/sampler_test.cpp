// The stratified sampler: within a pixel each 2D request forms a (0,m,2)-net over the first 2^m samples and each
// 1D request hits every 1/2^m stratum once; across pixels and dimensions the values are uniform (chi^2) and
// independent, so estimators stay unbiased; values depend only on (seed, pixel, sample index, dimension).
#include "core/sampler.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "support/chi2.h"

namespace kiln {
namespace {

std::vector<Vec2f> pixel_points(uint64_t seed, uint32_t px, uint32_t py, uint32_t dim, uint32_t n) {
  std::vector<Vec2f> pts;
  for (uint32_t i = 0; i < n; ++i) {
    Sampler s(seed, px, py, i);
    s.set_dimension(dim);
    pts.push_back(s.next_2d());
  }
  return pts;
}

// Skipping a 1D request (a value nobody reads) leaves every later value as drawing it would have, within the
// stratified dimensions and past them (the independent tail).
TEST(Sampler, SkippingARequestKeepsTheValuesAfterIt) {
  for (const uint32_t start : {3u, kStratifiedDimensions - 1, kStratifiedDimensions + 5}) {
    for (uint32_t index = 0; index < 16; ++index) {
      Sampler drawn(11, 4, 9, index), skipped(11, 4, 9, index);
      drawn.set_dimension(start);
      skipped.set_dimension(start);
      (void)drawn.next_float_if(true);
      EXPECT_EQ(skipped.next_float_if(false), 0.0f);
      EXPECT_EQ(drawn.dimension(), skipped.dimension());
      const Vec2f a = drawn.next_2d(), b = skipped.next_2d();
      EXPECT_EQ(a.x, b.x) << "from dimension " << start << ", sample " << index;
      EXPECT_EQ(a.y, b.y) << "from dimension " << start << ", sample " << index;
      EXPECT_EQ(drawn.next_float(), skipped.next_float());
    }
  }
}

// A dedicated stream (the shutter time) is stratified over a pixel's samples and reading it changes no other value:
// a scene that never asks for it renders exactly as before, one that does keeps every other dimension.
TEST(Sampler, DedicatedStreamIsStratifiedAndLeavesTheDimensionsAlone) {
  constexpr uint32_t kStream = 0x74696d65u, kN = 64;
  std::vector<int> strata(kN, 0);
  for (uint32_t i = 0; i < kN; ++i) {
    Sampler plain(9, 3, 4, i), timed(9, 3, 4, i);
    const float t = timed.dedicated_1d(kStream);
    ASSERT_GE(t, 0.0f);
    ASSERT_LT(t, 1.0f);
    ++strata[size_t(t * kN)];
    for (int d = 0; d < 80; ++d) ASSERT_EQ(plain.next_float(), timed.next_float()) << "dimension " << d;
    ASSERT_EQ(timed.dedicated_1d(kStream), t) << "a pure function of (seed, pixel, sample, stream)";
  }
  for (uint32_t k = 0; k < kN; ++k) EXPECT_EQ(strata[k], 1) << "stratum " << k;
  EXPECT_NE(Sampler(9, 3, 4, 0).dedicated_1d(kStream), Sampler(9, 3, 5, 0).dedicated_1d(kStream));
}

TEST(Sampler, SobolDimensionsAreTheZeroTwoSequence) {
  // First points of Sobol' dimensions 0 and 1 in index (not Gray-code) order: van der Corput and its (0,2) partner.
  const float x[] = {0.0f, 0.5f, 0.25f, 0.75f, 0.125f};
  const float y[] = {0.0f, 0.5f, 0.75f, 0.25f, 0.625f};
  for (uint32_t i = 0; i < 5; ++i) {
    EXPECT_EQ(float(reverse_bits(i)) * 0x1p-32f, x[i]) << i;
    EXPECT_EQ(float(sobol_dimension1(i)) * 0x1p-32f, y[i]) << i;
  }
}

TEST(Sampler, OwenScrambleIsABijectionThatKeepsPrefixes) {
  // Bits are flipped depending only on more significant bits: values sharing their top k bits keep sharing them.
  std::set<uint32_t> seen;
  for (uint32_t v = 0; v < 4096; ++v) seen.insert(owen_scramble(v << 20, 12345u) >> 20);
  EXPECT_EQ(seen.size(), 4096u);
  for (uint32_t v = 0; v < 1000; ++v) EXPECT_EQ(owen_scramble(v << 8, 99u) >> 24, owen_scramble((v << 8) | 0xffu, 99u) >> 24);
}

// Every elementary interval of area 1/2^m (2^a x 2^(m-a) cells, all a) holds exactly one of the first 2^m points.
TEST(Sampler, EachTwoDimensionalRequestIsANetWithinAPixel) {
  for (const uint32_t m : {4u, 6u, 8u})
    for (uint32_t dim = 0; dim < 12; ++dim) {
      const uint32_t n = 1u << m;
      const auto pts = pixel_points(3, 17, 5 + dim, dim, n);
      for (uint32_t a = 0; a <= m; ++a) {
        std::vector<int> count(n, 0);
        for (const Vec2f& p : pts) {
          const uint32_t cx = uint32_t(p.x * float(1u << a)), cy = uint32_t(p.y * float(1u << (m - a)));
          ++count[cx * (1u << (m - a)) + cy];
        }
        for (uint32_t c = 0; c < n; ++c) ASSERT_EQ(count[c], 1) << "m " << m << " dim " << dim << " a " << a << " cell " << c;
      }
    }
}

TEST(Sampler, EachOneDimensionalRequestIsStratifiedWithinAPixel) {
  const uint32_t n = 64;
  for (uint32_t dim = 0; dim < 8; ++dim) {
    std::vector<int> count(n, 0);
    for (uint32_t i = 0; i < n; ++i) {
      Sampler s(11, 4, 9, i);
      s.set_dimension(dim);
      ++count[uint32_t(s.next_float() * float(n))];
    }
    for (uint32_t c = 0; c < n; ++c) ASSERT_EQ(count[c], 1) << "dim " << dim << " stratum " << c;
  }
}

// Across pixels the values of one request are uniform, and two requests of one sample are independent: chi^2 on
// the pooled first sample of 2^18 pixels, for a 2D request and for pairs drawn from different dimensions.
TEST(Sampler, ValuesAreUniformAndDimensionsIndependentAcrossPixels) {
  constexpr int kBins = 16;
  const uint32_t pixels = 1u << 18;
  std::vector<uint64_t> joint(kBins * kBins, 0), cross(kBins * kBins, 0), deep(kBins * kBins, 0);
  for (uint32_t p = 0; p < pixels; ++p) {
    Sampler s(5, p % 512, p / 512, p % 7);
    s.set_dimension(2);
    const Vec2f a = s.next_2d();
    const float b = s.next_float();  // dimension 3
    s.set_dimension(kStratifiedDimensions + 1);  // the PCG tail
    const Vec2f c = s.next_2d();
    ++joint[size_t(int(a.x * kBins) * kBins + int(a.y * kBins))];
    ++cross[size_t(int(a.x * kBins) * kBins + int(b * kBins))];
    ++deep[size_t(int(c.x * kBins) * kBins + int(c.y * kBins))];
  }
  const std::vector<double> uniform(kBins * kBins, 1.0 / (kBins * kBins));
  for (const auto* h : {&joint, &cross, &deep}) {
    const auto r = test::chi2_discrete(*h, uniform, 0.01, 3);
    EXPECT_TRUE(r.passed) << r.message;
  }
}

// The samples of one pixel are not merely a fixed pattern: other pixels and seeds scramble them differently.
TEST(Sampler, PixelsAndSeedsAreScrambledIndependently) {
  const auto a = pixel_points(1, 0, 0, 2, 16), b = pixel_points(1, 1, 0, 2, 16), c = pixel_points(2, 0, 0, 2, 16);
  int same_ab = 0, same_ac = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    same_ab += a[i].x == b[i].x;
    same_ac += a[i].x == c[i].x;
  }
  EXPECT_LT(same_ab, 2);
  EXPECT_LT(same_ac, 2);
}

TEST(Sampler, DependsOnlyOnSeedPixelIndexAndDimension) {
  Sampler a(9, 100, 200, 300), b(9, 100, 200, 300);
  a.set_dimension(7);
  (void)b.next_2d();  // a different history ...
  b.set_dimension(7);  // ... then the same dimension
  EXPECT_EQ(a.next_float(), b.next_float());
  EXPECT_EQ(a.next_2d().y, b.next_2d().y);
  for (int k = 0; k < 1000; ++k) {
    const float v = a.next_float();
    ASSERT_TRUE(v >= 0.0f && v < 1.0f);
  }
}

}  // namespace
}  // namespace kiln
