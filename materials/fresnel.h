// Fresnel reflectance and Snell refraction in the local shading frame (normal +z).
#pragma once
#include <optional>

#include "core/color.h"
#include "core/frame.h"

namespace kiln {

// Unpolarised reflectance of a smooth dielectric interface. eta = eta_inside / eta_outside (outside is +z);
// cos_theta_o < 0 means the light arrives from inside. Returns 1 under total internal reflection.
float fresnel_dielectric(float cos_theta_o, float eta);

// Unpolarised reflectance of a conductor with complex index eta + i kappa (relative to the outside medium),
// evaluated exactly with complex arithmetic (pbrt-v4 FrComplex).
float fresnel_conductor(float cos_theta_o, float eta, float kappa);

// Per-channel complex index of refraction eta + i k of a conductor (pbrt-v4 conductors: RGB eta and k, relative
// to the outside medium).
struct RgbComplexIor {
  Rgb eta, k;
};

// fresnel_conductor per channel.
Rgb fresnel_conductor(float cos_theta_o, const RgbComplexIor& ior);

// Normal-incidence reflectance ((eta-1)^2 + kappa^2) / ((eta+1)^2 + kappa^2); kappa = 0 is the spec's
// R0 = ((eta-1)/(eta+1))^2.
float fresnel_r0(float eta, float kappa = 0.0f);

// Schlick's approximation R0 + (1 - R0)(1 - cos)^5, cos clamped to [0, 1].
float fresnel_schlick(float cos_theta, float r0);

// Specular reflection about +z.
inline Vec3f reflect_z(Vec3f w) { return {-w.x, -w.y, w.z}; }

struct Refraction {
  Vec3f wt;    // refracted direction, on the other side of the surface from wo
  float etap;  // eta of the side wt enters over eta of the side wo leaves (eta or 1/eta)
};

// Refracts wo through the interface with relative index eta = eta_inside / eta_outside. Empty under total
// internal reflection or when wo lies in the surface plane.
std::optional<Refraction> refract(Vec3f wo, float eta);

// Refracts wo through a (micro)facet with unit normal n on the outside's side (n.z >= 0): wo may lie on either
// side of the facet. Empty under total internal reflection or when wo lies in the facet plane.
std::optional<Refraction> refract(Vec3f wo, Vec3f n, float eta);

}  // namespace kiln
