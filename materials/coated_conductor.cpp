#include "materials/coated_conductor.h"

#include "materials/fresnel.h"

namespace kiln {

float CoatedConductor::albedo_estimate() const {
  const float r = fresnel_dielectric(1.0f, coat.eta);
  return r + (1.0f - r) * fresnel_conductor(1.0f, conductor.ior).average();
}

}  // namespace kiln
