// Lobe selection for BRDFs with a diffuse and a glossy lobe: the glossy lobe is sampled with probability
// proportional to its estimated albedo, es / (ed + es). Any fixed choice keeps the estimator unbiased because
// pdf() returns the same mixture; the albedo ratio keeps the weight f cos / pdf close to constant.
#pragma once

namespace kiln {

inline float glossy_lobe_probability(float diffuse_albedo, float glossy_albedo) {
  if (!(glossy_albedo > 0.0f)) return diffuse_albedo > 0.0f ? 0.0f : 0.5f;
  if (!(diffuse_albedo > 0.0f)) return 1.0f;
  return glossy_albedo / (diffuse_albedo + glossy_albedo);
}

}  // namespace kiln
