// Lambertian (ideal diffuse) reflection.
//
// Parameters:
//   reflectance  kd in [0, 1]^3; f = kd / pi, directional albedo kd at every angle.
// Sampling: cosine-weighted hemisphere, pdf cos(theta_i) / pi. Reciprocal and energy conserving.
// Like every surface BRDF here, it is one-sided in the local frame: wo.z > 0 and wi.z > 0, else 0 (Material
// makes surfaces two-sided by mirroring wo into +z).
#pragma once
#include <optional>

#include "core/sampling.h"
#include "materials/bsdf_sample.h"

namespace kiln {

struct Lambert {
  Rgb reflectance{0.5f};
  static constexpr bool kIgnoresLobeChoice = true;  // one lobe: sample() does not read uc

  // Defined here so that Material's dispatch inlines them: the sample then never goes through memory.
  Rgb eval(Vec3f wo, Vec3f wi) const {
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return Rgb(0.0f);
    return reflectance * kInvPi;
  }
  float pdf(Vec3f wo, Vec3f wi) const {
    if (!(wo.z > 0.0f)) return 0.0f;
    return cosine_hemisphere_pdf(wi.z);
  }
  std::optional<BsdfSample> sample(Vec3f wo, float /*uc*/, Vec2f u) const {
    if (!(wo.z > 0.0f)) return std::nullopt;
    const Vec3f wi = sample_cosine_hemisphere(u);
    const float pdf = cosine_hemisphere_pdf(wi.z);
    if (!(pdf > 0.0f)) return std::nullopt;  // a direction exactly on the horizon
    return BsdfSample{reflectance * kInvPi, wi, pdf, kLobeReflection | kLobeDiffuse};
  }
  uint32_t flags() const { return kLobeReflection | kLobeDiffuse; }
  // Normal-incidence albedo estimate, used to choose between this and a delta lobe.
  float albedo_estimate() const { return reflectance.average(); }
};

}  // namespace kiln
