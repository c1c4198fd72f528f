// Diffuse transmission (pbrt-v4 "diffusetransmission", its DiffuseTransmissionBxDF): a Lambertian lobe on each
// side of the surface, for thin translucent sheets (paper, leaves, lamp shades).
//
// Parameters:
//   reflectance    R in [0, 1]^3: f = R / pi for wi on the side of wo
//   transmittance  T in [0, 1]^3: f = T / pi for wi on the other side
// (pbrt's "scale" multiplies both before they are clamped to [0, 1]; scenes/material_mapping applies it.)
// Directional albedo R + T at every angle (energy conserving when R + T <= 1); reciprocal.
// Sampling: reflection with probability pr = max(R) / (max(R) + max(T)), else transmission, each cosine-weighted
// on its side: pdf = pr cos(theta_i) / pi or (1 - pr) |cos(theta_i)| / pi.
// One-sided like every surface BRDF here (written for wo.z > 0; Material mirrors wo.z < 0): transmission goes to
// wi.z < 0, so NEE must try lights on both sides (Material::has_surface_transmission). No change of medium or
// IOR across the surface.
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"

namespace kiln {

struct DiffuseTransmission {
  Rgb reflectance{0.25f};
  Rgb transmittance{0.25f};

  Rgb eval(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  uint32_t flags() const;
  float albedo_estimate() const { return (reflectance + transmittance).average(); }

 private:
  float reflection_probability() const;  // pr above; 0 when both R and T are black
};

}  // namespace kiln
