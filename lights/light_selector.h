// Chooses which light a next-event-estimation sample goes to, and reports the probability of that choice so
// integrators can weight by MIS. PowerProportional weights each light by power(light); Uniform gives every light
// the same weight. In both modes a light with zero power is never chosen; when no light has positive power,
// empty() is true.
#pragma once
#include <span>

#include "core/sampling.h"
#include "lights/light.h"

namespace kiln {

enum class LightSelection { PowerProportional, Uniform };

class LightSelector {
 public:
  LightSelector() = default;
  LightSelector(std::span<const Light> lights, LightSelection mode);
  bool empty() const { return dist_.size() == 0; }
  size_t size() const { return dist_.size(); }
  // Index of the chosen light and its probability; u in [0,1).
  size_t sample(float u, float* pmf) const { return dist_.sample(u, pmf); }
  float pmf(size_t light_index) const { return dist_.pmf(light_index); }

 private:
  Distribution1D dist_;
};

}  // namespace kiln
