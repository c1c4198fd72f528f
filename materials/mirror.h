// Ideal mirror (course MirrorReflectance; 2021 type="mirror"): all light leaves along the reflection of wo,
// weighted by the mirror colour. Two-sided (reflection about the local normal keeps the side of wo).
//
// Parameters:
//   reflectance  k_m (MirrorReflectance)
// eval and pdf are 0 (delta lobe); sample returns the reflection with f = k_m / |cos(theta_i)| and pdf 1.
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/specular_branch.h"

namespace kiln {

struct Mirror {
  Rgb reflectance{1.0f};

  Rgb eval(Vec3f, Vec3f) const { return Rgb(0.0f); }
  float pdf(Vec3f, Vec3f) const { return 0.0f; }
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  uint32_t flags() const { return kLobeReflection | kLobeSpecular; }
  // 0 or 1 branch (none when wo lies in the surface plane).
  int branches(Vec3f wo, SpecularBranch out[2]) const;
  float albedo_estimate(Vec3f) const { return reflectance.average(); }
};

// Picks one of a delta BSDF's branches with uc and turns it into a sample (shared by the delta BSDFs).
std::optional<BsdfSample> sample_branch(const SpecularBranch* branches, int count, float uc);

}  // namespace kiln
