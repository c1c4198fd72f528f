// Torrance-Sparrow microfacet BRDF as the course defines it (spec §4):
//   f = kd/pi [* (1 - F)] + ks D F G / (4 cos(theta_i) cos(theta_o))
//   D = (p+2)/(2 pi) cos^p(alpha_h)                        Blinn distribution (normalized: ∫ D cos(theta_h) = 1)
//   G = min(1, 2 (n.wh)(n.wo)/(wo.wh), 2 (n.wh)(n.wi)/(wo.wh))   Cook-Torrance V-cavity shadowing
//   F = Schlick R0 + (1 - R0)(1 - cos beta)^5, cos beta = wo.wh,  R0 = ((eta-1)^2 + kappa^2)/((eta+1)^2 + kappa^2)
//
// Parameters:
//   kd, ks      diffuse and specular reflectance
//   exponent    p >= 0 (BRDF <Exponent>)
//   eta, kappa  refractive index (2019 BRDF child RefractiveIndex, or 2021 material RefractionIndex) and
//               absorption index (2021 AbsorptionIndex; 0 otherwise). With kappa = 0 R0 is the spec's
//               ((eta-1)/(eta+1))^2; with kappa > 0 it is the exact conductor reflectance at normal incidence, so
//               the 2021 metals get their measured R0 while keeping the spec's Schlick angular falloff.
//   kd_fresnel  2021 kdfresnel="true": the diffuse term is weighted by (1 - F)
// Reciprocal; energy conserving for kd + ks <= 1. f = 0 unless wo.z > 0 and wi.z > 0.
// Sampling: w_h with pdf D(w_h) cos(theta_h) = (p+2)/(2 pi) cos^(p+1)(alpha_h), wi = reflect(wo, w_h), Jacobian
// 1/(4 wo.wh); diffuse lobe cosine-weighted; lobe chosen by the ratio of albedo estimates kd(1 - F_avg) : ks F_avg
// with F_avg = R0 + (1 - R0)/21, the cosine-weighted hemispherical average of Schlick's F.
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"

namespace kiln {

struct TorranceSparrow {
  Rgb kd{0.0f}, ks{0.5f};
  float exponent = 50.0f;
  float eta = 1.5f;
  float kappa = 0.0f;
  bool kd_fresnel = false;

  Rgb eval(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  uint32_t flags() const;

  float r0() const;
  float glossy_probability() const;
  float albedo_estimate() const;
  // The microfacet distribution and shadowing terms (exposed for tests).
  float distribution(float cos_theta_h) const;
  static float shadowing(Vec3f wo, Vec3f wi, Vec3f wh);
};

}  // namespace kiln
