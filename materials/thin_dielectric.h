// Thin dielectric (pbrt-v4 "thindielectric", its ThinDielectricBxDF): an infinitely thin slab of a dielectric, such
// as a window pane, with both faces smooth and parallel. Light that enters the slab bounces between its faces any
// number of times; every exit leaves either in the mirror direction or straight through (the slab has no
// thickness, so a transmitted ray is not displaced and not bent). Summing the geometric series of internal
// reflections with r = F(theta_o) (the same at both faces, by symmetry) and t = 1 - r:
//   R = r + t^2 r / (1 - r^2) = 2 r / (1 + r),   T = 1 - R   (no absorption: energy is conserved exactly)
// Two-sided and symmetric: wo may lie on either side. No change of medium or IOR across it: a transmitted ray
// carries etap = 1.
//
// Parameters:
//   eta  index of the slab relative to the surrounding medium (> 0; 1 = invisible)
// eval and pdf are 0 (delta lobes); sample picks reflection with probability R and transmission with T.
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/specular_branch.h"

namespace kiln {

struct ThinDielectric {
  float eta = 1.5f;

  Rgb eval(Vec3f, Vec3f) const { return Rgb(0.0f); }
  float pdf(Vec3f, Vec3f) const { return 0.0f; }
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  uint32_t flags() const { return kLobeReflection | kLobeTransmission | kLobeSpecular; }
  // Reflection (weight R) and straight transmission (weight T = 1 - R); transmission alone when eta = 1.
  int branches(Vec3f wo, SpecularBranch out[2]) const;
  // R(theta_o) of the slab, summed over its internal reflections.
  float reflectance(float cos_theta_o) const;
  float albedo_estimate(Vec3f) const { return 1.0f; }
};

}  // namespace kiln
