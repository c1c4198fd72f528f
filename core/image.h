// A float RGB image in scanline order (row 0 at the top).
#pragma once
#include <vector>

#include "core/color.h"

namespace kiln {

class Image {
 public:
  Image() = default;
  Image(int width, int height) : w_(width), h_(height), px_(size_t(width) * size_t(height)) {}
  int width() const { return w_; }
  int height() const { return h_; }
  Rgb& at(int x, int y) { return px_[size_t(y) * size_t(w_) + size_t(x)]; }
  const Rgb& at(int x, int y) const { return px_[size_t(y) * size_t(w_) + size_t(x)]; }
  std::vector<Rgb>& pixels() { return px_; }
  const std::vector<Rgb>& pixels() const { return px_; }

 private:
  int w_ = 0, h_ = 0;
  std::vector<Rgb> px_;
};

}  // namespace kiln
