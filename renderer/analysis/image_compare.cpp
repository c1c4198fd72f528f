#include "renderer/analysis/image_compare.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace kiln {
namespace {

// relMSE's denominator offset: keeps black reference pixels from dominating (as in Rousselle et al. 2011).
constexpr double kRelMseEpsilon = 1e-2;

void check_same_size(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw Error("images differ in size: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) + " vs " +
                std::to_string(b.width()) + "x" + std::to_string(b.height()));
}

// Counts a pixel pair that is not finite on either side; true when the pair may enter a metric.
bool usable(Rgb a, Rgb reference, NonFinitePixels& left_out) {
  const bool fa = a.is_finite(), fr = reference.is_finite();
  left_out.image += !fa;
  left_out.reference += !fr;
  return fa && fr;
}

}  // namespace

BlockStats block_luminance_stats(const Image& a, const Image& b, int block, double min_reference) {
  check_same_size(a, b);
  const int bx = (a.width() + block - 1) / block, by = (a.height() + block - 1) / block;
  std::vector<double> la(size_t(bx * by), 0.0), lb(size_t(bx * by), 0.0), n(size_t(bx * by), 0.0);
  double sum_a = 0, sum_b = 0, used = 0;
  BlockStats s;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      if (!usable(a.at(x, y), b.at(x, y), s.left_out)) continue;
      const size_t k = size_t((y / block) * bx + x / block);
      const double va = a.at(x, y).luminance(), vb = b.at(x, y).luminance();
      used += 1;
      la[k] += va;
      lb[k] += vb;
      n[k] += 1;
      sum_a += va;
      sum_b += vb;
    }
  const double mean_b = used > 0 ? sum_b / used : 0.0;
  std::vector<double> rel;
  for (size_t k = 0; k < la.size(); ++k) {
    if (n[k] == 0) continue;
    const double ma = la[k] / n[k], mb = lb[k] / n[k];
    if (mb <= min_reference * mean_b) continue;
    rel.push_back(std::abs(ma - mb) / mb);
  }
  s.blocks = rel.size();
  s.mean_ratio = sum_b > 0 ? sum_a / sum_b : 0.0;
  if (rel.empty()) return s;
  std::sort(rel.begin(), rel.end());
  s.median_rel = rel[rel.size() / 2];
  s.p95_rel = rel[std::min(rel.size() - 1, size_t(0.95 * double(rel.size())))];
  return s;
}

ErrorStats error_stats(const Image& a, const Image& b) {
  check_same_size(a, b);
  double se = 0, rel = 0;
  ErrorStats s;
  size_t n = 0;
  for (size_t i = 0; i < a.pixels().size(); ++i) {
    if (!usable(a.pixels()[i], b.pixels()[i], s.left_out)) continue;
    ++n;
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.pixels()[i][c]) - double(b.pixels()[i][c]);
      const double r = b.pixels()[i][c];
      se += d * d;
      rel += d * d / (r * r + kRelMseEpsilon);
    }
  }
  s.mse = n ? se / double(3 * n) : 0.0;
  s.rmse = std::sqrt(s.mse);
  s.rel_mse = n ? rel / double(3 * n) : 0.0;
  return s;
}

double ldr_match_fraction(const Image& a, const Image& b, int tol) {
  check_same_size(a, b);
  size_t ok = 0;
  for (size_t i = 0; i < a.pixels().size(); ++i) {
    bool good = true;
    for (int c = 0; c < 3; ++c) {
      const long va = std::lround(std::clamp(a.pixels()[i][c], 0.0f, 1.0f) * 255.0f);
      const long vb = std::lround(std::clamp(b.pixels()[i][c], 0.0f, 1.0f) * 255.0f);
      good &= std::abs(va - vb) <= tol;
    }
    ok += good;
  }
  return a.pixels().empty() ? 1.0 : double(ok) / double(a.pixels().size());
}

}  // namespace kiln
