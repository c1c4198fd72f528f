#include "materials/blinn_phong.h"

#include "core/sampling.h"
#include "materials/cos_denominator.h"
#include "materials/cos_power_lobe.h"
#include "materials/lobe_mixture.h"

namespace kiln {
namespace {

// At normal incidence theta_i = 2 theta_h and d(omega_i) = 4 cos(theta_h) d(omega_h); the lobe reaches the
// horizon at theta_h = 45 degrees, so with c = cos(theta_h) and c0 = cos 45°:
//   integral of cos^p(theta_h) d(omega_i)               = 8 pi (1 - c0^(p+2)) / (p+2)
//   integral of cos^p(theta_h) cos(theta_i) d(omega_i)  = 8 pi [2 (1 - c0^(p+4))/(p+4) - (1 - c0^(p+2))/(p+2)]
double normal_incidence_integral(double p, bool with_cos) {
  constexpr double kPiD = 3.14159265358979323846;
  const double c0 = std::sqrt(0.5);
  const double a = (1.0 - std::pow(c0, p + 2.0)) / (p + 2.0);
  if (!with_cos) return 8.0 * kPiD * a;
  const double b = (1.0 - std::pow(c0, p + 4.0)) / (p + 4.0);
  return 8.0 * kPiD * (2.0 * b - a);
}

Vec3f half_vector(Vec3f wo, Vec3f wi) { return normalize(wo + wi); }

}  // namespace

float half_vector_lobe_pdf(Vec3f wo, Vec3f wi, float n) {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
  const Vec3f wh = half_vector(wo, wi);
  const float cos_oh = dot(wo, wh);
  if (!(cos_oh > 0.0f)) return 0.0f;
  return cos_power_pdf(wh.z, n) / (4.0f * cos_oh);
}

std::optional<Vec3f> sample_half_vector_lobe(Vec3f wo, Vec2f u, float n) {
  const Vec3f wh = sample_cos_power(u, n);
  const float cos_oh = dot(wo, wh);
  if (!(cos_oh > 0.0f)) return std::nullopt;
  const Vec3f wi = normalize(2.0f * cos_oh * wh - wo);
  if (!(wi.z > 0.0f)) return std::nullopt;
  return wi;
}

uint32_t BlinnPhong::flags() const {
  uint32_t f = kLobeReflection;
  if (!kd.is_black()) f |= kLobeDiffuse;
  if (!ks.is_black()) f |= kLobeGlossy;
  return f;
}

float BlinnPhong::diffuse_albedo_at_normal() const { return variant == PhongVariant::ModifiedNormalized ? 1.0f : kPi; }

float BlinnPhong::glossy_albedo_at_normal() const {
  const double p = exponent;
  switch (variant) {
    case PhongVariant::Original:
      return float(normal_incidence_integral(p, false));
    case PhongVariant::Modified:
      return float(normal_incidence_integral(p, true));
    case PhongVariant::ModifiedNormalized:
      return float((p + 8.0) / (8.0 * 3.14159265358979323846) * normal_incidence_integral(p, true));
  }
  return 1.0f;
}

float BlinnPhong::glossy_probability() const {
  return glossy_lobe_probability(kd.average() * diffuse_albedo_at_normal(), ks.average() * glossy_albedo_at_normal());
}

float BlinnPhong::albedo_estimate() const {
  return kd.average() * diffuse_albedo_at_normal() + ks.average() * glossy_albedo_at_normal();
}

Rgb BlinnPhong::eval(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return Rgb(0.0f);
  const float lobe = cos_power(half_vector(wo, wi).z, exponent);
  switch (variant) {
    case PhongVariant::Original:
      return kd + ks * (lobe / cos_denominator(wi.z));
    case PhongVariant::Modified:
      return kd + ks * lobe;
    case PhongVariant::ModifiedNormalized:
      return kd * kInvPi + ks * ((exponent + 8.0f) * (kInvPi / 8.0f) * lobe);
  }
  return Rgb(0.0f);
}

float BlinnPhong::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
  const float pg = glossy_probability();
  return pg * half_vector_lobe_pdf(wo, wi, exponent) + (1.0f - pg) * cosine_hemisphere_pdf(wi.z);
}

std::optional<BsdfSample> BlinnPhong::sample(Vec3f wo, float uc, Vec2f u) const {
  if (!(wo.z > 0.0f)) return std::nullopt;
  const bool glossy = uc < glossy_probability();
  std::optional<Vec3f> wi = glossy ? sample_half_vector_lobe(wo, u, exponent) : sample_cosine_hemisphere(u);
  if (!wi || !(wi->z > 0.0f)) return std::nullopt;
  const float p = pdf(wo, *wi);
  if (!(p > 0.0f)) return std::nullopt;
  return BsdfSample{eval(wo, *wi), *wi, p, kLobeReflection | (glossy ? kLobeGlossy : kLobeDiffuse)};
}

}  // namespace kiln
