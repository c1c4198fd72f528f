#include "materials/conductor.h"

#include "materials/fresnel.h"
#include "materials/mirror.h"

namespace kiln {

float Conductor::fresnel(float cos_theta_o) const { return fresnel_conductor(cos_theta_o, eta, kappa); }

Rgb Conductor::fresnel_rgb(float cos_theta_o) const {
  return rgb_ior ? fresnel_conductor(cos_theta_o, *rgb_ior) : Rgb(fresnel(cos_theta_o));
}

int Conductor::branches(Vec3f wo, SpecularBranch out[2]) const {
  if (wo.z == 0.0f || !is_finite(wo)) return 0;
  out[0] = SpecularBranch{reflect_z(wo), reflectance * fresnel_rgb(wo.z), 1.0f, false, 1.0f};
  return 1;
}

std::optional<BsdfSample> Conductor::sample(Vec3f wo, float uc, Vec2f /*u*/) const {
  SpecularBranch b[2];
  return sample_branch(b, branches(wo, b), uc);
}

}  // namespace kiln
