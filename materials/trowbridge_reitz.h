// Anisotropic Trowbridge-Reitz (GGX) microfacet distribution with Smith's height-correlated masking-shadowing
// and visible-normal sampling (Heitz 2018), as pbrt-v4's TrowbridgeReitzDistribution defines it.
//
// Parameters:
//   alpha_x, alpha_y  roughness along the local x (pbrt: dpdu) and y axes. pbrt's "roughness" parameters become
//                     alpha through roughness_to_alpha (alpha = sqrt(roughness)) unless remaproughness is false.
//                     Below kSmoothAlpha on both axes the surface is "effectively smooth": the BxDFs using it
//                     switch to their delta (specular) form, as pbrt does.
//
//   D(wm)       = 1 / (pi ax ay (x^2/ax^2 + y^2/ay^2 + z^2)^2)          (wm = (x, y, z), unit, z > 0)
//   Lambda(w)   = (sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2) - 1) / 2
//   G1(w) = 1 / (1 + Lambda(w)),  G(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi))
//   D_w(wm)     = G1(w) / |cos(theta_w)| D(wm) max(0, sign(w.z) w . wm)   distribution of normals visible from w
// D is normalised in projected area (∫ D(wm) cos(theta_m) dwm = 1) and D_w is a density over wm for every w
// (∫ D_w(wm) dwm = 1, the "weak white furnace"). sample_visible draws wm from D_w for w on either side (it samples
// the normals visible from the side w lies on, always returning wm.z > 0).
#pragma once
#include "core/vec.h"

namespace kiln {

struct TrowbridgeReitz {
  // Both alphas below this: effectively smooth (pbrt-v4's threshold).
  static constexpr float kSmoothAlpha = 1e-3f;
  // Non-smooth alphas are raised to at least this, keeping D finite in float (pbrt-v4 does the same).
  static constexpr float kMinAlpha = 1e-4f;

  float alpha_x = 0.0f, alpha_y = 0.0f;

  TrowbridgeReitz() = default;
  TrowbridgeReitz(float ax, float ay);

  // pbrt's remapping of a user-facing roughness in [0, 1] to alpha.
  static float roughness_to_alpha(float roughness);

  bool effectively_smooth() const { return std::max(alpha_x, alpha_y) < kSmoothAlpha; }
  float d(Vec3f wm) const;
  float lambda(Vec3f w) const;
  float g1(Vec3f w) const { return 1.0f / (1.0f + lambda(w)); }
  float g(Vec3f wo, Vec3f wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }
  // Density of the normals visible from w, per unit solid angle of wm.
  float visible_d(Vec3f w, Vec3f wm) const;
  // Draws wm from visible_d(w, .); wm.z > 0.
  Vec3f sample_visible(Vec3f w, Vec2f u) const;
};

}  // namespace kiln
