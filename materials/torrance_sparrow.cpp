#include "materials/torrance_sparrow.h"

#include "core/sampling.h"
#include "materials/blinn_phong.h"
#include "materials/cos_denominator.h"
#include "materials/cos_power_lobe.h"
#include "materials/fresnel.h"
#include "materials/lobe_mixture.h"

namespace kiln {
namespace {

// Cosine-weighted hemispherical average of (1 - cos)^5: ∫ 2 c (1 - c)^5 dc = 1/21.
constexpr float kSchlickCosineAverage = 1.0f / 21.0f;

}  // namespace

float TorranceSparrow::r0() const { return fresnel_r0(eta, kappa); }

uint32_t TorranceSparrow::flags() const {
  uint32_t f = kLobeReflection;
  if (!kd.is_black()) f |= kLobeDiffuse;
  if (!ks.is_black()) f |= kLobeGlossy;
  return f;
}

float TorranceSparrow::distribution(float cos_theta_h) const {
  return (exponent + 2.0f) * kInv2Pi * cos_power(cos_theta_h, exponent);
}

float TorranceSparrow::shadowing(Vec3f wo, Vec3f wi, Vec3f wh) {
  const float cos_oh = dot(wo, wh);
  if (!(cos_oh > 0.0f)) return 0.0f;
  const float g_o = 2.0f * wh.z * wo.z / cos_oh;
  const float g_i = 2.0f * wh.z * wi.z / cos_oh;
  return std::clamp(std::min(g_o, g_i), 0.0f, 1.0f);
}

float TorranceSparrow::glossy_probability() const {
  const float r = r0();
  const float f_avg = r + (1.0f - r) * kSchlickCosineAverage;
  const float diffuse = kd.average() * (kd_fresnel ? 1.0f - f_avg : 1.0f);
  return glossy_lobe_probability(diffuse, ks.average() * f_avg);
}

float TorranceSparrow::albedo_estimate() const {
  const float r = r0();
  const float f_avg = r + (1.0f - r) * kSchlickCosineAverage;
  return kd.average() * (kd_fresnel ? 1.0f - f_avg : 1.0f) + ks.average() * f_avg;
}

Rgb TorranceSparrow::eval(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return Rgb(0.0f);
  const Vec3f wh = normalize(wo + wi);
  const float cos_oh = dot(wo, wh);
  const float F = fresnel_schlick(cos_oh, r0());
  const float D = distribution(wh.z);
  const float G = shadowing(wo, wi, wh);
  const float spec = D * F * G / (4.0f * cos_denominator(wi.z) * cos_denominator(wo.z));
  const Rgb diffuse = kd * (kInvPi * (kd_fresnel ? 1.0f - F : 1.0f));
  return diffuse + ks * spec;
}

float TorranceSparrow::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
  const float pg = glossy_probability();
  return pg * half_vector_lobe_pdf(wo, wi, exponent + 1.0f) + (1.0f - pg) * cosine_hemisphere_pdf(wi.z);
}

std::optional<BsdfSample> TorranceSparrow::sample(Vec3f wo, float uc, Vec2f u) const {
  if (!(wo.z > 0.0f)) return std::nullopt;
  const bool glossy = uc < glossy_probability();
  std::optional<Vec3f> wi = glossy ? sample_half_vector_lobe(wo, u, exponent + 1.0f) : sample_cosine_hemisphere(u);
  if (!wi || !(wi->z > 0.0f)) return std::nullopt;
  const float p = pdf(wo, *wi);
  if (!(p > 0.0f)) return std::nullopt;
  return BsdfSample{eval(wo, *wi), *wi, p, kLobeReflection | (glossy ? kLobeGlossy : kLobeDiffuse)};
}

}  // namespace kiln
