#include "materials/diffuse_transmission.h"

#include "core/sampling.h"

namespace kiln {

float DiffuseTransmission::reflection_probability() const {
  const float pr = reflectance.max_component(), pt = transmittance.max_component();
  return pr + pt > 0.0f ? pr / (pr + pt) : 0.0f;
}

uint32_t DiffuseTransmission::flags() const {
  uint32_t f = kLobeDiffuse;
  if (!reflectance.is_black()) f |= kLobeReflection;
  if (!transmittance.is_black()) f |= kLobeTransmission;
  return f;
}

Rgb DiffuseTransmission::eval(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || wi.z == 0.0f) return Rgb(0.0f);
  return (wi.z > 0.0f ? reflectance : transmittance) * kInvPi;
}

float DiffuseTransmission::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || wi.z == 0.0f || (reflectance.is_black() && transmittance.is_black())) return 0.0f;
  const float pr = reflection_probability();
  return (wi.z > 0.0f ? pr : 1.0f - pr) * cosine_hemisphere_pdf(std::abs(wi.z));
}

std::optional<BsdfSample> DiffuseTransmission::sample(Vec3f wo, float uc, Vec2f u) const {
  if (!(wo.z > 0.0f) || (reflectance.is_black() && transmittance.is_black())) return std::nullopt;
  const float pr = reflection_probability();
  Vec3f wi = sample_cosine_hemisphere(u);
  if (!(wi.z > 0.0f)) return std::nullopt;  // a direction exactly on the horizon
  const bool reflect = uc < pr;
  if (!reflect) wi.z = -wi.z;
  const float p = (reflect ? pr : 1.0f - pr) * cosine_hemisphere_pdf(std::abs(wi.z));
  if (!(p > 0.0f)) return std::nullopt;
  return BsdfSample{(reflect ? reflectance : transmittance) * kInvPi, wi, p,
                    kLobeDiffuse | (reflect ? kLobeReflection : kLobeTransmission)};
}

}  // namespace kiln
