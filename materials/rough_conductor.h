// Rough conductor (pbrt-v4's ConductorBxDF): Trowbridge-Reitz microfacet reflection with the exact per-channel
// Fresnel reflectance of a complex index of refraction.
//
// Parameters:
//   distribution  Trowbridge-Reitz alphas. Effectively smooth alphas make it a delta mirror: sample() returns the
//                 reflection with f = F / |cos(theta_i)| and pdf 1 (kLobeSpecular), eval and pdf are 0. A smooth
//                 pbrt "conductor" material is the delta Conductor; the smooth form serves CoatedConductor's base.
//   ior           eta + i k per RGB channel, relative to the outside. pbrt's "reflectance" form r is eta = 1,
//                 k = 2 sqrt(r) / sqrt(1 - r), whose normal-incidence reflectance is exactly r.
//
//   f(wo, wi) = D(wm) F(|wo . wm|) G(wo, wi) / (4 cos(theta_o) cos(theta_i)),   wm = normalize(wo + wi)
// Reciprocal. Single scattering only, so the albedo is below F (energy lost at high roughness, as in pbrt).
// Sampling: wm from the visible normals of wo, wi = reflect(wo, wm); pdf = D_wo(wm) / (4 |wo . wm|). Samples
// reflected below the horizon fail.
// One-sided like every surface BRDF here (wo.z > 0 and wi.z > 0, else 0; Material mirrors wo.z < 0).
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/trowbridge_reitz.h"

namespace kiln {

struct RoughConductor {
  TrowbridgeReitz distribution;
  RgbComplexIor ior{Rgb(0.2f, 0.92f, 1.1f), Rgb(3.91f, 2.45f, 2.14f)};
  static constexpr bool kIgnoresLobeChoice = true;  // one lobe: sample() does not read uc

  Rgb eval(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  bool is_specular() const { return distribution.effectively_smooth(); }
  uint32_t flags() const { return kLobeReflection | (is_specular() ? kLobeSpecular : kLobeGlossy); }
  // Normal-incidence Fresnel reflectance (channel average).
  float albedo_estimate() const { return fresnel_conductor(1.0f, ior).average(); }
};

}  // namespace kiln
