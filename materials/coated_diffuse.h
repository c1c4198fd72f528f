// Coated diffuse (pbrt-v4 "coateddiffuse", its CoatedDiffuseBxDF = LayeredBxDF<DielectricBxDF, DiffuseBxDF,
// twoSided>): a dielectric coat, smooth or rough, over a Lambertian base, with an optional scattering and
// absorbing medium between them, evaluated by the layered random walk (materials/layered.h, which documents the
// estimators, their determinism, the exit weights and the smooth coat's delta reflection).
//
// Parameters:
//   layers  the coat, thickness, albedo, g, max_depth, n_samples, exit_weight (materials/layered.h)
//   base    Lambert: the base reflectance in [0, 1]^3
// Two-sided: written for wo.z > 0 and mirrored by Material. Reflection only (the base does not transmit).
#pragma once
#include "materials/lambert.h"
#include "materials/layered.h"

namespace kiln {

// A named type (not an alias) so that the Material variant, messages and AOVs can tell the layered materials apart.
struct CoatedDiffuse : Layered<Lambert> {};

}  // namespace kiln
