#include "lights/emission_image.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace kiln {

EmissionImage::EmissionImage(Image texels, Rgb scale) : texels_(std::move(texels)) {
  if (texels_.width() <= 0 || texels_.height() <= 0) throw Error("the emission image is empty");
  double sum[3] = {0.0, 0.0, 0.0};
  for (Rgb& c : texels_.pixels()) {
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(c[i])) throw Error("the emission image holds a value that is not finite (inf or NaN)");
      c[i] = std::max(c[i], 0.0f) * scale[i];
      sum[i] += double(c[i]);
    }
  }
  const double n = double(texels_.pixels().size());
  mean_ = Rgb(float(sum[0] / n), float(sum[1] / n), float(sum[2] / n));
}

Rgb EmissionImage::radiance(Vec2f uv) const {
  const int w = texels_.width(), h = texels_.height();
  // Continuous texel coordinates: texel (i, j) covers [i, i + 1) x [j, j + 1), its centre at i + 0.5.
  const float x = uv.x * float(w) - 0.5f, y = (1.0f - uv.y) * float(h) - 0.5f;
  const float x0f = std::floor(x), y0f = std::floor(y);
  const float fx = x - x0f, fy = y - y0f;
  if (!std::isfinite(fx) || !std::isfinite(fy)) return Rgb(0.0f);
  const auto clamp_x = [w](float v) { return int(std::clamp(v, 0.0f, float(w - 1))); };
  const auto clamp_y = [h](float v) { return int(std::clamp(v, 0.0f, float(h - 1))); };
  const int xa = clamp_x(x0f), xb = clamp_x(x0f + 1.0f), ya = clamp_y(y0f), yb = clamp_y(y0f + 1.0f);
  const Rgb top = texels_.at(xa, ya) * (1.0f - fx) + texels_.at(xb, ya) * fx;
  const Rgb bottom = texels_.at(xa, yb) * (1.0f - fx) + texels_.at(xb, yb) * fx;
  return top * (1.0f - fy) + bottom * fy;
}

}  // namespace kiln
