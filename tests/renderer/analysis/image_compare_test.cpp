// The comparison metrics (kiln compare, --reference, the reference tests): a pixel that is not finite on either
// side is left out and counted, and every other pixel is measured as before.
#include <gtest/gtest.h>

#include <limits>

#include "renderer/analysis/image_compare.h"

namespace kiln {
namespace {

constexpr int kSize = 8;
constexpr int kBlock = 4;

Image ramp(float scale) {
  Image img(kSize, kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) img.at(x, y) = Rgb(scale * float(1 + x + kSize * y));
  return img;
}

TEST(ImageCompare, AnInfiniteReferencePixelIsLeftOutAndCounted) {
  const Image a = ramp(1.1f);
  Image ref = ramp(1.0f);
  const ErrorStats clean = error_stats(a, ref);
  ref.at(3, 5) = Rgb(std::numeric_limits<float>::infinity());
  const ErrorStats e = error_stats(a, ref);
  const BlockStats b = block_luminance_stats(a, ref, kBlock);
  EXPECT_TRUE(std::isfinite(e.mse) && std::isfinite(e.rel_mse));
  EXPECT_TRUE(std::isfinite(b.median_rel) && std::isfinite(b.p95_rel) && std::isfinite(b.mean_ratio));
  EXPECT_EQ(e.left_out.reference, 1u);
  EXPECT_EQ(e.left_out.image, 0u);
  EXPECT_EQ(b.left_out.reference, 1u);
  EXPECT_EQ(b.blocks, size_t(kSize / kBlock) * size_t(kSize / kBlock));
  // Every block still has a = 1.1 ref (a 10% error), whichever pixels it keeps.
  EXPECT_NEAR(b.median_rel, 0.1, 1e-5);
  EXPECT_NEAR(b.p95_rel, 0.1, 1e-5);
  EXPECT_NEAR(b.mean_ratio, 1.1, 1e-5);
  // The MSE is the mean over the 63 pixels that remain.
  const double d = double(a.at(3, 5).r) - double(ramp(1.0f).at(3, 5).r);
  const double removed = d * d;
  EXPECT_NEAR(e.mse, (clean.mse * kSize * kSize - removed) / (kSize * kSize - 1), 1e-9 * clean.mse);
}

TEST(ImageCompare, ANanInTheImageIsCountedNotSpread) {
  Image a = ramp(1.0f);
  a.at(0, 0) = Rgb(std::numeric_limits<float>::quiet_NaN());
  const ErrorStats e = error_stats(a, ramp(1.0f));
  EXPECT_EQ(e.left_out.image, 1u);
  EXPECT_EQ(e.mse, 0.0);
}

}  // namespace
}  // namespace kiln
