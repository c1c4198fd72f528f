// Smooth conductor (2021 type="conductor"): mirror reflection weighted by MirrorReflectance times the exact
// Fresnel reflectance of the complex index eta + i kappa. Two-sided.
//
// Parameters:
//   reflectance  k_m (MirrorReflectance)
//   eta          RefractionIndex (real part, relative to air)
//   kappa        AbsorptionIndex (imaginary part)
//   rgb_ior      per-channel eta + i k (pbrt-v4 conductors with roughness 0); when set it replaces eta and kappa
// eval and pdf are 0 (delta lobe); sample returns the reflection with f = k_m F / |cos(theta_i)| and pdf 1.
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/specular_branch.h"

namespace kiln {

struct Conductor {
  Rgb reflectance{1.0f};
  float eta = 0.37f;
  float kappa = 2.82f;
  std::optional<RgbComplexIor> rgb_ior;

  Rgb eval(Vec3f, Vec3f) const { return Rgb(0.0f); }
  float pdf(Vec3f, Vec3f) const { return 0.0f; }
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  uint32_t flags() const { return kLobeReflection | kLobeSpecular; }
  int branches(Vec3f wo, SpecularBranch out[2]) const;
  float fresnel(float cos_theta_o) const;  // scalar eta, kappa
  Rgb fresnel_rgb(float cos_theta_o) const;  // rgb_ior when set, else fresnel() in every channel
  float albedo_estimate(Vec3f wo) const { return (reflectance * fresnel_rgb(wo.z)).average(); }
};

}  // namespace kiln
