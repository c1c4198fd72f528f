// What a medium is at one point: absorption and scattering coefficients (per unit length) and emitted radiance.
// The phase function is the medium's own (one Henyey-Greenstein g per medium, as in pbrt-v4).
#pragma once
#include "core/color.h"

namespace kiln {

struct MediumProperties {
  Rgb sigma_a, sigma_s;
  Rgb le;  // emitted radiance; a medium emits sigma_a * le per unit length
};

}  // namespace kiln
