// Lambertian (ideal diffuse) reflection.
//
// Parameters:
//   reflectance  kd in [0, 1]^3; f = kd / pi, directional albedo kd at every angle.
// Sampling: cosine-weighted hemisphere, pdf cos(theta_i) / pi. Reciprocal and energy conserving.
// Like every surface BRDF here, it is one-sided in the local frame: wo.z > 0 and wi.z > 0, else 0 (Material
// makes surfaces two-sided by mirroring wo into +z).
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"

namespace kiln {

struct Lambert {
  Rgb reflectance{0.5f};

  Rgb eval(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  uint32_t flags() const { return kLobeReflection | kLobeDiffuse; }
  // Normal-incidence albedo estimate, used to choose between this and a delta lobe.
  float albedo_estimate() const { return reflectance.average(); }
};

}  // namespace kiln
