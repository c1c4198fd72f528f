// Per-pixel sample sums. Each pixel is only ever touched by the thread rendering its tile, and its samples are
// added in sample-index order, so the result is bit-identical for any thread count, tile order or wave split.
#pragma once
#include <vector>

#include "core/image.h"

namespace kiln {

// Sums of a pixel's samples, each already multiplied by its pixel-filter weight (renderer/film/pixel_filter.h): with
// negative filter lobes a weighted sample can be negative, and lum2 then still sums its square, so the variance
// AOV is the variance of the weighted estimator.
struct PixelSum {
  double r = 0, g = 0, b = 0;
  double lum2 = 0;  // sum of squared luminance (per-pixel variance AOV)
  double even_r = 0, even_g = 0, even_b = 0;  // sums over the even sample indices (adaptive sampling's estimate)
  uint32_t n = 0;   // samples taken (per pixel: an interrupted wave or adaptive sampling leaves different counts)
  bool converged = false;  // adaptive sampling stopped this pixel
};

class Film {
 public:
  Film() = default;
  Film(int width, int height) : w_(width), h_(height), px_(size_t(width) * size_t(height)) {}
  int width() const { return w_; }
  int height() const { return h_; }
  PixelSum& at(int x, int y) { return px_[size_t(y) * size_t(w_) + size_t(x)]; }
  const PixelSum& at(int x, int y) const { return px_[size_t(y) * size_t(w_) + size_t(x)]; }
  // Mean radiance per pixel.
  Image mean() const;
  // Variance of the pixel mean's luminance (sample variance / n), as RGB grey.
  Image variance_of_mean() const;

 private:
  int w_ = 0, h_ = 0;
  std::vector<PixelSum> px_;
};

}  // namespace kiln
