// Floor for BRDFs that divide by cos(theta) (original Phong / Blinn-Phong, Torrance-Sparrow).
#pragma once
#include "core/math.h"

namespace kiln {

// Directions with cos(theta) below this are within float rounding of the horizon; flooring the denominator
// keeps f finite there (f * cos then underestimates by at most this relative amount of a vanishing term).
inline constexpr float kMinCosDenominator = 1e-7f;

inline float cos_denominator(float cos_theta) { return std::max(cos_theta, kMinCosDenominator); }

}  // namespace kiln
