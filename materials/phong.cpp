#include "materials/phong.h"

#include "core/sampling.h"
#include "materials/cos_denominator.h"
#include "materials/cos_power_lobe.h"
#include "materials/fresnel.h"
#include "materials/lobe_mixture.h"

namespace kiln {

uint32_t Phong::flags() const {
  uint32_t f = kLobeReflection;
  if (!kd.is_black()) f |= kLobeDiffuse;
  if (!ks.is_black()) f |= kLobeGlossy;
  return f;
}

float Phong::diffuse_albedo_at_normal() const { return variant == PhongVariant::ModifiedNormalized ? 1.0f : kPi; }

// At normal incidence the lobe around the normal lies wholly above the horizon:
// integral of cos^p over the hemisphere = 2 pi/(p+1); with the extra cos(theta_i) = 2 pi/(p+2).
float Phong::glossy_albedo_at_normal() const {
  switch (variant) {
    case PhongVariant::Original:
      return 2.0f * kPi / (exponent + 1.0f);
    case PhongVariant::Modified:
      return 2.0f * kPi / (exponent + 2.0f);
    case PhongVariant::ModifiedNormalized:
      return 1.0f;
  }
  return 1.0f;
}

float Phong::glossy_probability() const {
  return glossy_lobe_probability(kd.average() * diffuse_albedo_at_normal(), ks.average() * glossy_albedo_at_normal());
}

float Phong::albedo_estimate() const {
  return kd.average() * diffuse_albedo_at_normal() + ks.average() * glossy_albedo_at_normal();
}

Rgb Phong::eval(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return Rgb(0.0f);
  const float lobe = cos_power(dot(reflect_z(wo), wi), exponent);
  switch (variant) {
    case PhongVariant::Original:
      return kd + ks * (lobe / cos_denominator(wi.z));
    case PhongVariant::Modified:
      return kd + ks * lobe;
    case PhongVariant::ModifiedNormalized:
      return kd * kInvPi + ks * ((exponent + 2.0f) * kInv2Pi * lobe);
  }
  return Rgb(0.0f);
}

float Phong::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
  const float pg = glossy_probability();
  return pg * cos_power_pdf(dot(reflect_z(wo), wi), exponent) + (1.0f - pg) * cosine_hemisphere_pdf(wi.z);
}

std::optional<BsdfSample> Phong::sample(Vec3f wo, float uc, Vec2f u) const {
  if (!(wo.z > 0.0f)) return std::nullopt;
  const bool glossy = uc < glossy_probability();
  const Vec3f wi = glossy ? Frame(reflect_z(wo)).to_world(sample_cos_power(u, exponent)) : sample_cosine_hemisphere(u);
  if (!(wi.z > 0.0f)) return std::nullopt;  // the part of the lobe below the horizon
  const float p = pdf(wo, wi);
  if (!(p > 0.0f)) return std::nullopt;
  return BsdfSample{eval(wo, wi), wi, p, kLobeReflection | (glossy ? kLobeGlossy : kLobeDiffuse)};
}

}  // namespace kiln
