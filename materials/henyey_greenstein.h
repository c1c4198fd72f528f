// Henyey-Greenstein phase function, the scattering medium of CoatedDiffuse's layer (pbrt-v4 HGPhaseFunction).
//
// Parameters:
//   g  asymmetry in (-1, 1): > 0 scatters forward, < 0 backward, 0 isotropically (1 / (4 pi)); |g| < 1e-3 is
//      taken as 0.
//
// Both directions point away from the scattering point (pbrt's convention): light arriving along -wo continues
// along wi, so forward scattering is wi = -wo and
//   p(wo, wi) = (1 - g^2) / (4 pi (1 + g^2 + 2 g (wo . wi))^(3/2)).
// Sampling inverts the CDF of the scattering angle exactly, so the pdf equals p.
#pragma once
#include <optional>

#include "core/vec.h"

namespace kiln {

struct PhaseSample {
  Vec3f wi;
  float p;    // phase function value, equal to pdf
  float pdf;
};

struct HenyeyGreenstein {
  float g = 0.0f;

  float p(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const { return p(wo, wi); }
  std::optional<PhaseSample> sample(Vec3f wo, Vec2f u) const;
};

}  // namespace kiln
