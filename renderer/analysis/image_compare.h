// Image error metrics: noise-aware block statistics against reference renders, and the MSE family used by the
// error-against-run-time report.
#pragma once
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace kiln {

// A pixel that is not finite in either image (a reference's overflowed half, a NaN in a render) is left out of
// every metric, so one such pixel cannot turn them all into NaN; the counts say how many were left out.
struct NonFinitePixels {
  size_t image = 0, reference = 0;
};

struct BlockStats {
  double median_rel = 0;  // median over blocks of |lum_a - lum_b| / lum_b
  double p95_rel = 0;     // 95th percentile of the same
  double mean_ratio = 0;  // mean luminance of a / mean luminance of b
  size_t blocks = 0;
  NonFinitePixels left_out;
};

// Both images averaged over block x block pixel squares; blocks whose reference luminance is below
// min_reference (relative to the image mean) are skipped, since a relative error means nothing there.
BlockStats block_luminance_stats(const Image& a, const Image& reference, int block, double min_reference = 1e-3);

struct ErrorStats {
  double mse = 0, rmse = 0;
  double rel_mse = 0;  // mean of (a - b)^2 / (b^2 + eps), per channel (Rousselle et al.'s relMSE)
  NonFinitePixels left_out;
};
ErrorStats error_stats(const Image& a, const Image& reference);

// Fraction of 8-bit pixels whose every channel is within tol of the reference.
double ldr_match_fraction(const Image& a, const Image& reference, int tol);

}  // namespace kiln
