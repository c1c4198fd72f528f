// Coated conductor (pbrt-v4 "coatedconductor", its CoatedConductorBxDF = LayeredBxDF<DielectricBxDF,
// ConductorBxDF, twoSided>): a dielectric coat, smooth or rough, over a conductor, smooth or rough, with an
// optional scattering and absorbing medium between them, evaluated by the layered random walk (materials/layered.h,
// which documents the estimators, their determinism, the exit weights and the delta lobes of smooth layers).
//
// Parameters:
//   coat         the interface: eta (inside / outside) and its Trowbridge-Reitz roughness
//   conductor    the base: its Trowbridge-Reitz roughness (effectively smooth = a mirror) and its complex index
//                eta + i k RELATIVE TO THE COAT (pbrt-v4 divides the conductor's eta and k by the coat's eta;
//                scenes/material_mapping does the same)
//   thickness, albedo, g, max_depth, n_samples, exit_weight  the layer stack (materials/layered.h)
// Two-sided: written for wo.z > 0 and mirrored by Material. Reflection only.
#pragma once
#include <optional>

#include "materials/layered.h"

namespace kiln {

struct CoatedConductor {
  RoughDielectric coat{1.5f, TrowbridgeReitz{}};
  RoughConductor conductor;
  float thickness = 0.01f;
  Rgb albedo{0.0f};
  float g = 0.0f;
  int max_depth = 10;
  int n_samples = 1;
  LayeredExitWeight exit_weight = LayeredExitWeight::Consistent;

  Rgb eval(Vec3f wo, Vec3f wi) const { return layered().eval(wo, wi); }
  float pdf(Vec3f wo, Vec3f wi) const { return layered().pdf(wo, wi); }
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const { return layered().sample(wo, uc, u); }
  uint32_t flags() const { return layered().flags(); }
  // Coat reflectance at normal incidence plus the conductor's normal-incidence reflectance seen through it.
  float albedo_estimate() const;

 private:
  Layered<RoughConductor> layered() const {
    return {LayerStack{coat, thickness, albedo, g, max_depth, n_samples, exit_weight}, conductor};
  }
};

}  // namespace kiln
