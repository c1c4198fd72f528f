#include "core/sampling.h"

#include <algorithm>

namespace kiln {

Distribution1D::Distribution1D(std::span<const float> weights) : pmf_(weights.size()), cdf_(weights.size() + 1) {
  auto usable = [](float w) { return w > 0.0f && std::isfinite(w); };
  double sum = 0.0;
  for (float w : weights)
    if (usable(w)) sum += w;
  // A weight whose float pmf underflows to 0 would still own a (vanishing) CDF interval, so it could be returned
  // with pmf 0 and divide by zero in an estimator; it is treated as zero weight instead.
  cdf_[0] = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    const double w = (usable(weights[i]) && float(weights[i] / sum) > 0.0f) ? weights[i] : 0.0;
    cdf_[i + 1] = cdf_[i] + w;
  }
  total_ = cdf_.back();
  for (size_t i = 0; i < weights.size(); ++i) {
    pmf_[i] = total_ > 0.0 ? float((cdf_[i + 1] - cdf_[i]) / total_) : 0.0f;
  }
  if (total_ > 0.0)
    for (double& c : cdf_) c /= total_;
}

namespace {
constexpr size_t kLinearScanSize = 8;
}  // namespace

size_t Distribution1D::sample(float u, float* pmf, float* u_remapped) const {
  if (pmf_.empty() || total_ <= 0.0) {
    if (pmf) *pmf = 0.0f;
    return 0;
  }
  // First index whose upper CDF bound exceeds u; zero-weight entries are never returned. Short tables (a scene's
  // few lights, a light's few triangles: sampled at every path vertex) are scanned, which finds the same index.
  const double ud = double(u);
  size_t i = 0;
  if (pmf_.size() <= kLinearScanSize) {
    while (i + 1 < pmf_.size() && !(cdf_[i + 1] > ud)) ++i;
  } else {
    i = size_t(std::distance(cdf_.begin() + 1, std::upper_bound(cdf_.begin() + 1, cdf_.end(), ud)));
  }
  i = std::min(i, pmf_.size() - 1);
  while (i > 0 && pmf_[i] == 0.0f) --i;
  if (pmf) *pmf = pmf_[i];
  if (u_remapped) {
    const double w = cdf_[i + 1] - cdf_[i];
    *u_remapped = w > 0.0 ? std::min(float((double(u) - cdf_[i]) / w), kOneMinusEpsilon) : 0.0f;
  }
  return i;
}

}  // namespace kiln
