// Coated conductor (pbrt-v4 "coatedconductor", its CoatedConductorBxDF = LayeredBxDF<DielectricBxDF,
// ConductorBxDF, twoSided>): a dielectric coat, smooth or rough, over a conductor, smooth or rough, with an
// optional scattering and absorbing medium between them, evaluated by the layered random walk (materials/layered.h,
// which documents the estimators, their determinism, the exit weights and the delta lobes of smooth layers).
//
// Parameters:
//   layers  the coat: eta (inside / outside) and its Trowbridge-Reitz roughness; thickness, albedo, g, max_depth,
//           n_samples, exit_weight (materials/layered.h)
//   base    RoughConductor: its Trowbridge-Reitz roughness (effectively smooth = a mirror) and its complex index
//           eta + i k RELATIVE TO THE COAT (pbrt-v4 divides the conductor's eta and k by the coat's eta;
//           scenes/material_mapping does the same)
// Two-sided: written for wo.z > 0 and mirrored by Material. Reflection only.
#pragma once
#include "materials/layered.h"
#include "materials/rough_conductor.h"

namespace kiln {

struct CoatedConductor : Layered<RoughConductor> {};

}  // namespace kiln
