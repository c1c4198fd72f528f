// Pixel reconstruction filters, used by filter importance sampling (pbrt-v4, "Filter importance sampling", Ernst
// et al. 2006): each camera sample's film position is drawn around the pixel centre with density proportional to
// |f|, and its radiance is multiplied by weight = f / (pdf * ∫f). The pixel value stays the plain mean of its
// weighted samples, an unbiased estimate of ∫ f L / ∫ f: no sample is shared between pixels (no splatting), so
// pixels stay independent, images are bit-identical for any thread count, and --spp-range parts merge exactly.
// Filters with negative lobes (Mitchell) give samples of negative weight; weight magnitudes are about
// ∫|f| / ∫f, so the per-pixel variance (the film's squared-luminance sum) rises by that factor squared.
//
// Profiles, all separable f(x, y) = g(x) g(y), with radius r = width / 2 (width as in Cycles: the full extent):
//   box              g = 1 on [-r, r]                    (default: width 1, the pixel's own area)
//   triangle         g = r - |x|                         (default width 2, pbrt's radius 1)
//   gaussian         g = max(0, G(x) - G(r)), sigma = width / 6  (pbrt's form; default width 3, pbrt's radius 1.5,
//                    sigma 0.5). Cycles' Gaussian does not subtract G(r) (a 1% difference at the tails).
//   blackman-harris  Cycles' window over [-r, r]         (default width 1.5, Cycles' default filter)
//   mitchell         Mitchell-Netravali, B = C = 1/3, on x in [-2, 2] scaled to [-r, r] (default width 4, pbrt's)
// Box and triangle are sampled exactly (weight 1); the others from a piecewise-constant table of |g|
// (kFilterTableSize bins per axis, as pbrt's FilterSampler) with the weight correcting the remainder.
//
// `--filter gaussian:0.01` (the smallest width Cycles accepts) samples within 0.005 px of pixel centres.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec.h"
#include "scenes/scene.h"

namespace kiln {

inline constexpr int kFilterTableSize = 256;
static_assert((kFilterTableSize & (kFilterTableSize - 1)) == 0, "u * kFilterTableSize must be exact");

struct FilterSample {
  Vec2f offset;        // from the pixel centre, in pixels
  float weight = 1.0f;  // f / (pdf * ∫f): 1 for box and triangle, near ±∫|f|/∫f otherwise
};

class PixelFilter {
 public:
  explicit PixelFilter(const PixelFilterDesc& desc = {});
  FilterSample sample(Vec2f u) const;
  // The filter profile f(x, y) at an offset from the pixel centre (unnormalised; 0 outside the radius).
  float evaluate(Vec2f p) const { return profile(p.x) * profile(p.y); }
  float radius() const { return desc_.radius; }
  // ∫f and ∫|f| over the filter's square.
  double integral() const { return g_integral_ * g_integral_; }
  double abs_integral() const { return g_abs_integral_ * g_abs_integral_; }

 private:
  float profile(float x) const;  // g
  float sample_1d(float u, float& weight) const;
  int find_bin(float u, int from) const;

  PixelFilterDesc desc_;
  double g_integral_ = 0, g_abs_integral_ = 0;
  std::vector<float> cdf_;       // kFilterTableSize + 1 entries, tabulated filters only
  std::vector<float> bin_pdf_;   // density of each bin (per pixel)
  // guide_[j]: the bin holding u = j / kFilterTableSize, so that a sample's bin is found by a short forward scan
  // instead of a binary search over the whole table (the same bin: images do not change).
  std::vector<uint16_t> guide_;
  // Gaussian: 2 sigma^2 and G(r), computed once (profile() runs twice per camera sample).
  double gauss_s2_ = 1.0, gauss_at_radius_ = 0.0;
};

// "NAME[:WIDTH]" with NAME box, triangle, gaussian, blackman-harris or mitchell and WIDTH the full width in pixels
// (default per filter, see above). Throws kiln::Error naming --filter when the text is not such a filter.
PixelFilterDesc parse_pixel_filter(const std::string& text);
// The filter a camera renders with: the --filter text when given, else the scene's filter, else box 1 px.
PixelFilterDesc pixel_filter_for(const CameraDesc& camera, const std::optional<std::string>& filter_text);
// "blackman-harris:1.5" etc.
std::string describe_pixel_filter(const PixelFilterDesc& desc);

}  // namespace kiln
