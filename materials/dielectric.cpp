#include "materials/dielectric.h"

#include "materials/fresnel.h"
#include "materials/mirror.h"

namespace kiln {

int Dielectric::branches(Vec3f wo, SpecularBranch out[2]) const {
  if (wo.z == 0.0f || !is_finite(wo)) return 0;
  float R = fresnel_dielectric(wo.z, eta);
  const std::optional<Refraction> t = R < 1.0f ? refract(wo, eta) : std::nullopt;
  if (!t) R = 1.0f;  // total internal reflection (also when float rounding puts refraction at the TIR edge)
  int n = 0;
  if (R > 0.0f) out[n++] = SpecularBranch{reflect_z(wo), Rgb(R), R, false, 1.0f};
  if (t) {
    const float T = 1.0f - R;
    out[n++] = SpecularBranch{t->wt, Rgb(T / (t->etap * t->etap)), T, true, t->etap};
  }
  return n;
}

std::optional<BsdfSample> Dielectric::sample(Vec3f wo, float uc, Vec2f /*u*/) const {
  SpecularBranch b[2];
  return sample_branch(b, branches(wo, b), uc);
}

}  // namespace kiln
