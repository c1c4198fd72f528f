#include "materials/lambert.h"

#include "core/sampling.h"

namespace kiln {

Rgb Lambert::eval(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return Rgb(0.0f);
  return reflectance * kInvPi;
}

float Lambert::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f)) return 0.0f;
  return cosine_hemisphere_pdf(wi.z);
}

std::optional<BsdfSample> Lambert::sample(Vec3f wo, float /*uc*/, Vec2f u) const {
  if (!(wo.z > 0.0f)) return std::nullopt;
  const Vec3f wi = sample_cosine_hemisphere(u);
  const float pdf = cosine_hemisphere_pdf(wi.z);
  if (!(pdf > 0.0f)) return std::nullopt;  // a direction exactly on the horizon
  return BsdfSample{reflectance * kInvPi, wi, pdf, kLobeReflection | kLobeDiffuse};
}

}  // namespace kiln
