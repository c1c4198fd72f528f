#include "materials/thin_dielectric.h"

#include "materials/fresnel.h"
#include "materials/mirror.h"

namespace kiln {

float ThinDielectric::reflectance(float cos_theta_o) const {
  const float r = fresnel_dielectric(std::abs(cos_theta_o), eta);
  // r + (1 - r)^2 r / (1 - r^2) simplified; exact for r = 1 (grazing) as well.
  return 2.0f * r / (1.0f + r);
}

int ThinDielectric::branches(Vec3f wo, SpecularBranch out[2]) const {
  if (wo.z == 0.0f || !is_finite(wo)) return 0;
  const float R = reflectance(wo.z), T = 1.0f - R;
  int n = 0;
  if (R > 0.0f) out[n++] = SpecularBranch{reflect_z(wo), Rgb(R), R, false, 1.0f};
  if (T > 0.0f) out[n++] = SpecularBranch{-wo, Rgb(T), T, true, 1.0f};
  return n;
}

std::optional<BsdfSample> ThinDielectric::sample(Vec3f wo, float uc, Vec2f /*u*/) const {
  SpecularBranch b[2];
  return sample_branch(b, branches(wo, b), uc);
}

}  // namespace kiln
