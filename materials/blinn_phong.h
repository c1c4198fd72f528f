// Blinn-Phong BRDF in the course's three forms (spec §4). alpha_h is the angle between the normal and the half
// vector w_h = normalize(wi + wo) (the course note's normalized formula writes alpha_r; the half-vector angle
// is what it intends, spec §14.5).
//
// Parameters:
//   kd, ks    diffuse and specular reflectance (DiffuseReflectance, SpecularReflectance)
//   exponent  p >= 0 (BRDF <Exponent>, or PhongExponent for the classic course shading)
//   variant   Original:            f = kd + ks cos^p(alpha_h) / cos(theta_i)   (the classic course shading)
//             Modified:            f = kd + ks cos^p(alpha_h)
//             ModifiedNormalized:  f = kd/pi + ks (p+8)/(8 pi) cos^p(alpha_h)
// The non-normalized forms have no 1/pi (albedo can exceed 1). The (p+8)/(8 pi) factor is the usual
// approximation of the exact normalization: at normal incidence the ks term's albedo is up to ~7% above 1
// (largest near p = 11) and tends to 1 as p grows; this is the model as specified.
// Modified forms are reciprocal, Original is not. f = 0 unless wo.z > 0 and wi.z > 0.
// Sampling: w_h with pdf (p+1)/(2 pi) cos^p(alpha_h) around the normal, wi = reflect(wo, w_h), pdf
// p_h / (4 wo.w_h); reflections below the horizon are failed samples. Diffuse lobe cosine-weighted; lobe chosen
// by the ratio of normal-incidence albedos (lobe_mixture.h).
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/phong_variant.h"

namespace kiln {

struct BlinnPhong {
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
  float albedo_estimate() const;
};

// pdf of the half-vector lobe sampler producing wi from wo (both above the horizon), exponent n:
// (n+1)/(2 pi) cos^n(theta_h) / (4 wo.w_h). Shared with Torrance-Sparrow.
float half_vector_lobe_pdf(Vec3f wo, Vec3f wi, float n);
// Samples that pdf; empty when the reflection falls below the horizon.
std::optional<Vec3f> sample_half_vector_lobe(Vec3f wo, Vec2f u, float n);

}  // namespace kiln
