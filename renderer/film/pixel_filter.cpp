#include "renderer/film/pixel_filter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "core/math.h"

namespace kiln {
namespace {

// Midpoint-rule points per table bin for the bin masses and ∫g (the profiles are smooth inside a bin apart from
// Mitchell's zero crossings and the Gaussian's kink at the radius).
constexpr int kQuadraturePerBin = 64;
// Widths beyond this blur more than any production filter; a typo such as "gaussian:15" is reported instead.
constexpr float kMaxFilterWidth = 16.0f;

double mitchell_1d(double x, double b, double c) {
  x = std::abs(x);
  if (x <= 1.0) return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6.0;
  if (x <= 2.0)
    return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6.0;
  return 0.0;
}

// Cycles' Blackman-Harris window (kernel/film: filter_func_blackman_harris) over [-r, r].
double blackman_harris_1d(double x, double r) {
  const double t = 2.0 * 3.14159265358979323846 * (x / (2.0 * r) + 0.5);
  return 0.35875 - 0.48829 * std::cos(t) + 0.14128 * std::cos(2.0 * t) - 0.01168 * std::cos(3.0 * t);
}

struct FilterName {
  const char* name;
  PixelFilterKind kind;
  float default_width;
};
constexpr FilterName kFilterNames[] = {{"box", PixelFilterKind::Box, 1.0f},
                                       {"triangle", PixelFilterKind::Triangle, 2.0f},
                                       {"gaussian", PixelFilterKind::Gaussian, 3.0f},
                                       {"blackman-harris", PixelFilterKind::BlackmanHarris, 1.5f},
                                       {"mitchell", PixelFilterKind::Mitchell, 4.0f}};

}  // namespace

PixelFilter::PixelFilter(const PixelFilterDesc& desc) : desc_(desc) {
  const double r = desc_.radius;
  if (!(r > 0.0) || !std::isfinite(r)) throw Error("pixel filter: radius must be positive, got " + std::to_string(r));
  gauss_s2_ = 2.0 * double(desc_.sigma) * double(desc_.sigma);
  gauss_at_radius_ = std::exp(-r * r / gauss_s2_);
  switch (desc_.kind) {
    case PixelFilterKind::Box:
      g_integral_ = g_abs_integral_ = 2.0 * r;
      return;
    case PixelFilterKind::Triangle:
      g_integral_ = g_abs_integral_ = r * r;
      return;
    default:
      break;
  }
  // Tabulated: bin masses of |g|, their running sum, and ∫g, by the midpoint rule in double.
  const double h = 2.0 * r / kFilterTableSize, dq = h / kQuadraturePerBin;
  std::vector<double> mass(kFilterTableSize, 0.0);
  for (int i = 0; i < kFilterTableSize; ++i)
    for (int k = 0; k < kQuadraturePerBin; ++k) {
      const double g = profile(float(-r + double(i) * h + (k + 0.5) * dq));
      mass[size_t(i)] += std::abs(g) * dq;
      g_integral_ += g * dq;
    }
  double total = 0.0;
  for (double m : mass) total += m;
  g_abs_integral_ = total;
  if (!(total > 0.0) || !(g_integral_ > 0.0)) throw Error("pixel filter: profile integrates to zero");
  cdf_.assign(kFilterTableSize + 1, 0.0f);
  bin_pdf_.resize(kFilterTableSize);
  double run = 0.0;
  for (int i = 0; i < kFilterTableSize; ++i) {
    run += mass[size_t(i)];
    cdf_[size_t(i) + 1] = float(run / total);
    bin_pdf_[size_t(i)] = float(mass[size_t(i)] / (total * h));
  }
  cdf_.back() = 1.0f;
  guide_.resize(kFilterTableSize);
  for (int j = 0; j < kFilterTableSize; ++j) guide_[size_t(j)] = uint16_t(find_bin(float(j) / kFilterTableSize, 0));
}

// The last bin i with cdf[i] <= u (empty bins are passed over), searching forward from a bin known to satisfy it.
int PixelFilter::find_bin(float u, int from) const {
  int i = from;
  while (i < kFilterTableSize - 1 && cdf_[size_t(i) + 1] <= u) ++i;
  return i;
}

float PixelFilter::profile(float x) const {
  const float r = desc_.radius;
  if (std::abs(x) > r) return 0.0f;
  switch (desc_.kind) {
    case PixelFilterKind::Box:
      return 1.0f;
    case PixelFilterKind::Triangle:
      return r - std::abs(x);
    case PixelFilterKind::Gaussian:
      return float(std::max(0.0, std::exp(-double(x) * x / gauss_s2_) - gauss_at_radius_));
    case PixelFilterKind::BlackmanHarris:
      return float(blackman_harris_1d(x, r));
    case PixelFilterKind::Mitchell:
      return float(mitchell_1d(2.0 * double(x) / r, desc_.b, desc_.c));
  }
  return 0.0f;
}

float PixelFilter::sample_1d(float u, float& weight) const {
  const float r = desc_.radius;
  switch (desc_.kind) {
    case PixelFilterKind::Box:
      weight = 1.0f;
      return (2.0f * u - 1.0f) * r;
    case PixelFilterKind::Triangle:  // inverse CDF of the tent: pdf (r - |x|) / r², weight exactly 1
      weight = 1.0f;
      return u < 0.5f ? r * (std::sqrt(2.0f * u) - 1.0f) : r * (1.0f - std::sqrt(2.0f * (1.0f - u)));
    default:
      break;
  }
  // The bin i with cdf[i] <= u < cdf[i + 1] (never an empty bin), then uniform inside it. u * kFilterTableSize is
  // exact (a power of two), so the guide's bin never lies past u's.
  const int i = find_bin(u, guide_[size_t(std::min(int(u * float(kFilterTableSize)), kFilterTableSize - 1))]);
  const float lo = cdf_[size_t(i)], hi = cdf_[size_t(i) + 1];
  const float frac = hi > lo ? std::min((u - lo) / (hi - lo), kOneMinusEpsilon) : 0.5f;
  const float h = 2.0f * r / float(kFilterTableSize);
  const float x = std::clamp(-r + (float(i) + frac) * h, -r, r);
  weight = float(double(profile(x)) / (double(bin_pdf_[size_t(i)]) * g_integral_));
  return x;
}

FilterSample PixelFilter::sample(Vec2f u) const {
  FilterSample s;
  float wx = 1.0f, wy = 1.0f;
  s.offset.x = sample_1d(u.x, wx);
  s.offset.y = sample_1d(u.y, wy);
  s.weight = wx * wy;
  return s;
}

PixelFilterDesc parse_pixel_filter(const std::string& text) {
  const size_t colon = text.find(':');
  const std::string name = text.substr(0, colon);
  const FilterName* found = nullptr;
  for (const FilterName& f : kFilterNames)
    if (name == f.name) found = &f;
  if (!found)
    throw Error("--filter", "", "unknown filter '" + name + "' (box, triangle, gaussian, blackman-harris, mitchell)");
  float width = found->default_width;
  if (colon != std::string::npos) {
    const std::string w = text.substr(colon + 1);
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (w.empty() || *end != '\0' || !(v > 0.0) || !(v <= kMaxFilterWidth))
      throw Error("--filter", "", "width '" + w + "' of '" + text + "' is not a number of pixels in (0, " +
                                      std::to_string(int(kMaxFilterWidth)) + "]");
    width = float(v);
  }
  PixelFilterDesc d;
  d.kind = found->kind;
  d.radius = 0.5f * width;
  d.sigma = width / 6.0f;
  return d;
}

PixelFilterDesc pixel_filter_for(const CameraDesc& camera, const std::optional<std::string>& filter_text) {
  if (filter_text) return parse_pixel_filter(*filter_text);
  return camera.filter.value_or(PixelFilterDesc{});
}

std::string describe_pixel_filter(const PixelFilterDesc& desc) {
  const char* name = "box";
  for (const FilterName& f : kFilterNames)
    if (f.kind == desc.kind) name = f.name;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s:%g", name, double(2.0f * desc.radius));
  return buf;
}

}  // namespace kiln
