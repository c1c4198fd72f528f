// Adaptive sampling with Cycles' stopping rule, decided per pixel from that pixel's own samples only.
//
// The film keeps, next to the sum I of a pixel's n samples, the sum of its even-indexed samples (doubled: A). Both
// I/n and A/n estimate the pixel; their difference, (mean of odd - mean of even) / 2, has the standard error of the
// pixel mean as its spread. Cycles' error (Dammertz et al. 2010, "A hierarchical automatic stopping condition for
// Monte Carlo global illumination", section 2.1, as in kernel/film/adaptive_sampling.h) is
//     e = (|I.r - A.r| + |I.g - A.g| + |I.b - A.b|) / n / (1e-4 + sqrt((I.r + I.g + I.b) / n)),
// an absolute error scaled by the square root of the pixel's brightness. A pixel stops once e < 5 * threshold
// (Cycles' factor 5 on its "Noise Threshold"). It is tested only at fixed sample counts: every kAdaptiveStep
// samples once past the minimum, i.e. after n samples when n % 16 == 0 and n > min_spp + 1 (Cycles'
// AdaptiveSampling::need_filter). So whether pixel p stops after n samples depends on p's first n samples alone:
// the result is bit-identical for any thread count, tile order and wave split. Unlike Cycles, a pixel that has
// not converged does not keep its neighbours sampling (Cycles' filter_x/filter_y pass): that would make one
// pixel's sample count depend on another's.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "renderer/film/film.h"

namespace kiln {

inline constexpr uint32_t kAdaptiveStep = 16;
// Cycles multiplies the user's threshold by this ("gives arguably more intuitive values").
inline constexpr double kAdaptiveThresholdScale = 5.0;

struct AdaptiveSampling {
  float threshold = 0.01f;  // Cycles' Noise Threshold (its default 0.01)
  uint32_t min_spp = 0;     // 0: Cycles' automatic minimum, max(4, ceil(16 / threshold^0.3)); 64 at 0.01

  uint32_t min_samples() const {
    if (min_spp > 0) return std::max<uint32_t>(4, min_spp);
    return std::max<uint32_t>(4, uint32_t(std::ceil(16.0f / std::pow(threshold, 0.3f))));
  }
  // Whether a pixel that has taken n samples is tested now.
  bool check_due(uint32_t n) const { return n % kAdaptiveStep == 0 && n > min_samples() + 1; }
  static double error(const PixelSum& p) {
    if (p.n == 0) return INFINITY;
    const double inv = 1.0 / double(p.n);
    const double diff = (std::abs(p.r - 2.0 * p.even_r) + std::abs(p.g - 2.0 * p.even_g) +
                         std::abs(p.b - 2.0 * p.even_b)) * inv;
    return diff / (1e-4 + std::sqrt(std::max(0.0, (p.r + p.g + p.b) * inv)));
  }
  bool converged(const PixelSum& p) const { return error(p) < kAdaptiveThresholdScale * double(threshold); }
};

}  // namespace kiln
