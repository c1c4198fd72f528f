#include "lights/light_selector.h"

#include <vector>

namespace kiln {

LightSelector::LightSelector(std::span<const Light> lights, LightSelection mode) {
  std::vector<float> weights(lights.size(), 0.0f);
  bool any = false;
  for (size_t i = 0; i < lights.size(); ++i) {
    // A light that emits nothing is never chosen, in either mode: its samples could only waste shadow rays.
    const float p = power(lights[i]);
    if (!(p > 0.0f)) continue;
    // A light so bright its power overflows still deserves a share; cap it rather than let Distribution1D drop it.
    weights[i] = mode == LightSelection::Uniform ? 1.0f : std::min(p, std::numeric_limits<float>::max());
    any = true;
  }
  if (any) dist_ = Distribution1D(weights);
}

}  // namespace kiln
