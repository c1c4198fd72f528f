// Phong BRDF in the course's three forms (spec §4). alpha_r is the angle between wo and the mirror reflection
// of wi (equivalently wi and the reflection of wo); cos(alpha_r) is clamped at 0.
//
// Parameters:
//   kd, ks    diffuse and specular reflectance (DiffuseReflectance, SpecularReflectance)
//   exponent  p >= 0 (BRDF <Exponent>)
//   variant   Original:            f = kd + ks cos^p(alpha_r) / cos(theta_i)
//             Modified:            f = kd + ks cos^p(alpha_r)
//             ModifiedNormalized:  f = kd/pi + ks (p+2)/(2 pi) cos^p(alpha_r)
// The non-normalized forms are the course's LDR forms (no 1/pi, albedo can exceed 1); only ModifiedNormalized
// conserves energy for kd + ks <= 1. Modified forms are reciprocal, Original is not. f = 0 unless wo.z > 0 and
// wi.z > 0.
// Sampling: the glossy lobe has pdf (p+1)/(2 pi) cos^p(alpha_r) around the mirror direction of wo (the part of
// it below the horizon is a failed sample); the diffuse lobe is cosine-weighted; the lobe is chosen by the
// ratio of normal-incidence albedos (lobe_mixture.h).
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/phong_variant.h"

namespace kiln {

struct Phong {
  Rgb kd{0.5f}, ks{0.0f};
  float exponent = 1.0f;
  PhongVariant variant = PhongVariant::ModifiedNormalized;

  Rgb eval(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  uint32_t flags() const;

  // Exact directional albedos at normal incidence of the kd term per unit kd and of the ks term per unit ks.
  float diffuse_albedo_at_normal() const;
  float glossy_albedo_at_normal() const;
  float glossy_probability() const;
  float albedo_estimate() const;  // normal-incidence albedo averaged over channels
};

}  // namespace kiln
