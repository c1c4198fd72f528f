// Smooth dielectric interface (2019: non-zero Transparency; 2021: type="dielectric"): Fresnel-weighted mirror
// reflection and Snell refraction, with total internal reflection.
//
// Parameters:
//   eta  RefractionIndex of the inside relative to the outside (air). The local +z is the geometric OUTSIDE
//        (integrators must not flip the frame of a dielectric): wo.z > 0 arrives from outside, wo.z < 0 from
//        inside.
// Transport mode: radiance. Refracted radiance is scaled by 1/etap^2 (etap = eta of the side wi lies in over
// eta of the side of wo), so the transmitted branch weighs (1 - F)/etap^2: entering glass scales by 1/eta^2,
// leaving by eta^2, and a path that enters and leaves a closed object gets exactly (1-F1)(1-F2).
// Beer-Lambert absorption inside is not part of this struct: the integrator applies Material::transmittance.
// eval and pdf are 0 (delta lobes); sample picks reflection with probability F and refraction with 1 - F.
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/specular_branch.h"

namespace kiln {

struct Dielectric {
  float eta = 1.5f;

  Rgb eval(Vec3f, Vec3f) const { return Rgb(0.0f); }
  float pdf(Vec3f, Vec3f) const { return 0.0f; }
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  uint32_t flags() const { return kLobeReflection | kLobeTransmission | kLobeSpecular; }
  // Reflection (weight F) and refraction (weight (1-F)/etap^2); only reflection (weight 1) under total internal
  // reflection; only refraction when F = 0 (eta = 1).
  int branches(Vec3f wo, SpecularBranch out[2]) const;
  float albedo_estimate(Vec3f) const { return 1.0f; }
};

}  // namespace kiln
