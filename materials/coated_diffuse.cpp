#include "materials/coated_diffuse.h"

#include "materials/fresnel.h"

namespace kiln {

float CoatedDiffuse::albedo_estimate() const {
  const float r = fresnel_dielectric(1.0f, coat.eta);
  return r + (1.0f - r) * reflectance.average();
}

}  // namespace kiln
