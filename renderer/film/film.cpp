#include "renderer/film/film.h"

namespace kiln {

Image Film::mean() const {
  Image img(w_, h_);
  for (size_t i = 0; i < px_.size(); ++i) {
    const double inv = px_[i].n > 0 ? 1.0 / double(px_[i].n) : 0.0;
    img.pixels()[i] = Rgb(float(px_[i].r * inv), float(px_[i].g * inv), float(px_[i].b * inv));
  }
  return img;
}

Image Film::variance_of_mean() const {
  Image img(w_, h_);
  for (size_t i = 0; i < px_.size(); ++i) {
    const PixelSum& p = px_[i];
    if (p.n < 2) continue;
    const double n = double(p.n);
    const double mean_lum = (0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b) / n;
    const double var = std::max(0.0, (p.lum2 / n - mean_lum * mean_lum) * n / (n - 1.0));
    img.pixels()[i] = Rgb(float(var / n));
  }
  return img;
}

}  // namespace kiln
