// Dielectric interface with Trowbridge-Reitz microfacets (pbrt-v4 DielectricBxDF; Walter et al. 2007): rough
// reflection AND transmission in one non-delta BSDF. It is also the coat of CoatedDiffuse, smooth or rough.
//
// Parameters:
//   eta           index of the inside relative to the outside. The local +z is the geometric OUTSIDE: wo.z > 0
//                 arrives from outside, wo.z < 0 from inside (integrators must not flip the frame of a material
//                 with this lobe; Material::oriented() says so).
//   distribution  Trowbridge-Reitz alphas. Effectively smooth (or eta = 1) it degenerates to the smooth interface:
//                 sample() returns specular reflection / refraction with probabilities F and 1 - F, eval and pdf
//                 are 0. As a Material surface it is only built rough (a smooth pbrt dielectric maps onto the
//                 delta Dielectric); the smooth form serves CoatedDiffuse's coat.
//
// With the generalised half vector wm = normalize(wo + etap wi) facing +z (etap = 1 for reflection, else the
// index of wi's side over wo's side) and F = fresnel_dielectric(wo . wm, eta):
//   reflection    f = D(wm) G(wo, wi) F / |4 cos(theta_o) cos(theta_i)|
//   transmission  f = D(wm) G(wo, wi) (1 - F) |(wi . wm)(wo . wm)| / |cos(theta_i) cos(theta_o) (wi . wm + wo . wm / etap)^2|
//                 divided by etap^2 in Radiance mode (radiance is compressed entering a denser medium).
// Microfacets facing away from wo or wi contribute nothing. Reciprocity is the adjoint relation
// f_radiance(wo, wi) = f_importance(wi, wo); in radiance mode f(wo, wi) / eta_o^2 = f(wi, wo) / eta_i^2 (eta of
// the side each direction lies on).
// Sampling: wm from the normals visible from wo, then reflection with probability F(wo . wm), else refraction
// through wm; pdf = D_wo(wm) / (4 |wo . wm|) * F for reflection and D_wo(wm) |wi . wm| / (wi . wm + wo . wm /
// etap)^2 * (1 - F) for transmission. A `lobes` mask (kLobeReflection / kLobeTransmission) restricts sampling to
// one of them, the pdf then being conditional on it (pbrt's BxDFReflTransFlags). Samples that leave on the wrong
// side fail; transmission samples carry eta = etap for the integrator's eta_scale.
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/trowbridge_reitz.h"

namespace kiln {

struct RoughDielectric {
  // Handles wo on either side itself (transmits, and is not symmetric in eta): Material passes wo and wi as they
  // are instead of mirroring them into +z.
  static constexpr bool kHandlesBothSides = true;

  float eta = 1.5f;
  TrowbridgeReitz distribution;

  bool is_specular() const { return eta == 1.0f || distribution.effectively_smooth(); }

  Rgb eval(Vec3f wo, Vec3f wi, Transport mode = Transport::Radiance) const { return Rgb(f(wo, wi, mode)); }
  float f(Vec3f wo, Vec3f wi, Transport mode = Transport::Radiance) const;
  float pdf(Vec3f wo, Vec3f wi, Transport mode = Transport::Radiance, uint32_t lobes = kSampleAll) const;
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u, Transport mode = Transport::Radiance,
                                   uint32_t lobes = kSampleAll) const;
  uint32_t flags() const;
  float albedo_estimate() const { return 1.0f; }
};

}  // namespace kiln
