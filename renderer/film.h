// Per-pixel sample sums. Each pixel is only ever touched by the thread rendering its tile, and its samples are
// added in sample-index order, so the result is bit-identical for any thread count, tile order or wave split.
#pragma once
#include <vector>

#include "core/image.h"

namespace kiln {

struct PixelSum {
  double r = 0, g = 0, b = 0;
  double lum2 = 0;  // sum of squared luminance (per-pixel variance AOV)
  uint32_t n = 0;   // samples taken (per pixel: an interrupted wave leaves pixels with different counts)
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
