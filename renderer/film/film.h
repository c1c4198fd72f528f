// Per-pixel sample sums. Each pixel is only ever touched by the thread rendering its tile, and its samples are
// added in sample-index order, so the result is bit-identical for any thread count, tile order or wave split.
// add_sample is the one place a sample is accumulated: its colour and, when the film keeps them (the geometric
// AOVs), what the sample saw (renderer/film/visible_surface.h), both with the sample's filter weight, so every output
// of a pixel is one filtered estimate over the same samples (crop, sample range, cancellation and merge alike).
#pragma once
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "renderer/film/visible_surface.h"

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

// Sums of what a pixel's samples saw, each times its filter weight (a sample that saw nothing adds zero).
struct SurfaceSum {
  double albedo[3] = {0, 0, 0};
  double n[3] = {0, 0, 0};
  double p[3] = {0, 0, 0};
  double z = 0;
};

class Film {
 public:
  Film() = default;
  Film(int width, int height) : w_(width), h_(height), px_(size_t(width) * size_t(height)) {}
  int width() const { return w_; }
  int height() const { return h_; }
  PixelSum& at(int x, int y) { return px_[index(x, y)]; }
  const PixelSum& at(int x, int y) const { return px_[index(x, y)]; }

  // From now on the film also sums what the samples saw (before the first sample: for the geometric AOVs).
  void keep_surfaces() { surfaces_.assign(px_.size(), SurfaceSum{}); }
  bool keeps_surfaces() const { return !surfaces_.empty(); }

  // Sample `index` of pixel (x, y): radiance L, pixel-filter weight `weight`, what it saw (ignored unless the film
  // keeps surfaces). Samples of a pixel arrive in index order, from the one thread that renders the pixel.
  void add_sample(int x, int y, uint32_t index, Rgb L, float weight, const VisibleSurface& visible);

  // Mean radiance per pixel.
  Image mean() const;
  // Variance of the pixel mean's luminance (sample variance / n), as RGB grey.
  Image variance_of_mean() const;
  // The filtered mean of what the samples of pixel (x, y) saw, over all its samples (found: the pixel has samples).
  // Only for a film that keeps surfaces.
  VisibleSurface surface_mean(int x, int y) const;

 private:
  size_t index(int x, int y) const { return size_t(y) * size_t(w_) + size_t(x); }
  int w_ = 0, h_ = 0;
  std::vector<PixelSum> px_;
  std::vector<SurfaceSum> surfaces_;  // empty unless kept
};

}  // namespace kiln
