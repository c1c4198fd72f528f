#include "renderer/film/film.h"

namespace kiln {
namespace {

void add_weighted(double (&sum)[3], Vec3f v, float weight) {
  sum[0] += double(v.x * weight);
  sum[1] += double(v.y * weight);
  sum[2] += double(v.z * weight);
}

Vec3f mean_of(const double (&sum)[3], double inv) {
  return {float(sum[0] * inv), float(sum[1] * inv), float(sum[2] * inv)};
}

}  // namespace

void Film::add_sample(int x, int y, uint32_t index, Rgb L, float weight, const VisibleSurface& visible) {
  const size_t i = this->index(x, y);
  PixelSum& px = px_[i];
  L = L * weight;
  px.r += L.r;
  px.g += L.g;
  px.b += L.b;
  const double lum = L.luminance();
  px.lum2 += lum * lum;
  if (index % 2 == 0) {
    px.even_r += L.r;
    px.even_g += L.g;
    px.even_b += L.b;
  }
  ++px.n;
  if (surfaces_.empty() || !visible.found) return;
  SurfaceSum& s = surfaces_[i];
  add_weighted(s.albedo, Vec3f{visible.albedo.r, visible.albedo.g, visible.albedo.b}, weight);
  add_weighted(s.n, visible.n, weight);
  add_weighted(s.p, visible.p, weight);
  s.z += double(visible.z * weight);
}

VisibleSurface Film::surface_mean(int x, int y) const {
  const size_t i = index(x, y);
  VisibleSurface v;
  if (px_[i].n == 0 || surfaces_.empty()) return v;
  const double inv = 1.0 / double(px_[i].n);
  const SurfaceSum& s = surfaces_[i];
  const Vec3f a = mean_of(s.albedo, inv);
  v.albedo = Rgb(a.x, a.y, a.z);
  v.n = mean_of(s.n, inv);
  v.p = mean_of(s.p, inv);
  v.z = float(s.z * inv);
  v.found = true;
  return v;
}

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
