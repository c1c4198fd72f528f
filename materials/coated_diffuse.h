// Coated diffuse (pbrt-v4 "coateddiffuse", its CoatedDiffuseBxDF = LayeredBxDF<DielectricBxDF, DiffuseBxDF,
// twoSided>): a dielectric coat, smooth or rough, over a Lambertian base, with an optional scattering and
// absorbing medium between them, evaluated by the layered random walk (materials/layered.h, which documents the
// estimators, their determinism, the exit weights and the smooth coat's delta reflection).
//
// Parameters:
//   reflectance  Lambertian base reflectance in [0, 1]^3
//   coat, thickness, albedo, g, max_depth, n_samples, exit_weight  the layer stack (materials/layered.h)
// Two-sided: written for wo.z > 0 and mirrored by Material. Reflection only (the base does not transmit).
#pragma once
#include <optional>

#include "materials/layered.h"

namespace kiln {

struct CoatedDiffuse {
  Rgb reflectance{0.5f};
  RoughDielectric coat{1.5f, TrowbridgeReitz{}};
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
  // Coat reflectance at normal incidence plus the base seen through the coat.
  float albedo_estimate() const;

 private:
  Layered<Lambert> layered() const {
    return {LayerStack{coat, thickness, albedo, g, max_depth, n_samples, exit_weight}, Lambert{reflectance}};
  }
};

}  // namespace kiln
