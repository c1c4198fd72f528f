// The one place where scene-file materials become Kiln materials (CENG795 XML spec §4-§5, CS171 JSON).
//
// Surface BRDF:
//   * MaterialDesc.brdf -> SceneDesc::brdfs[i]:
//       OriginalPhong / ModifiedPhong [normalized]           -> Phong (Original / Modified / ModifiedNormalized)
//       OriginalBlinnPhong / ModifiedBlinnPhong [normalized] -> BlinnPhong (same variants)
//       TorranceSparrow -> TorranceSparrow; eta from the 2019 BRDF child RefractiveIndex, else the material's
//                          RefractionIndex (2021); kappa = AbsorptionIndex; kdfresnel as given
//       Lambert         -> Lambert(kd)  (CS171 "diffuse": f = color / pi)
//     The BRDF's Exponent is used; PhongExponent is ignored (spec §14.11).
//   * No BRDF: the classic course shading k_d max(0, cos) + k_s cos^PhongExponent(alpha_h), i.e.
//     BlinnPhong Original (f = kd + ks cos^p(alpha_h) / cos(theta_i)).
//   * A surface whose kd and ks are both black is dropped (NoSurface). Without ks the specular lobe is dropped: a
//     Phong / Blinn-Phong form or Torrance-Sparrow (without kdfresnel) becomes Lambert(pi * f) with f its constant
//     diffuse value (kd for the Original and Modified forms, kd/pi for the normalized ones and Torrance-Sparrow).
// Delta part:
//   * type Mirror -> Mirror(k_m); Conductor -> Conductor(k_m, RefractionIndex, AbsorptionIndex);
//     Dielectric -> Dielectric(RefractionIndex), absorption = AbsorptionCoefficient (2021).
//   * type Plain (2019 inference): non-zero Transparency -> Dielectric(RefractionIndex) with per-unit-length
//     transmittance a = Transparency, i.e. absorption = -ln(a) (+ AbsorptionCoefficient); a is clamped to
//     [kMinTransparency, 1]. Otherwise non-zero MirrorReflectance -> Mirror. A dielectric already reflects, so
//     Transparency wins over MirrorReflectance.
//   * roughness = Roughness (perturbs delta directions; 0 = perfect).
// degamma="true": AmbientReflectance, DiffuseReflectance, SpecularReflectance and MirrorReflectance are
//   gamma-decoded with c^2.2 (spec §14.3: the common reading); Transparency / absorption are not colours.
//
// CS171 loaders should fill MaterialDesc as: "diffuse" -> a BrdfDesc of kind Lambert referenced by brdf, with
// diffuse = color; "specular" -> type Mirror, mirror = color; "translucent" -> type Dielectric with
// refraction_index = 1.5 and has_refraction_index = true (no IOR key exists; 1.5 is glass).
//
// pbrt-v4 materials (MaterialDesc::pbrt set; the course fields are then ignored):
//   * diffuse        -> Lambert(reflectance clamped to [0, 1])
//   * conductor      -> alpha = sqrt(roughness) per axis (u along the frame's x = pbrt's dpdu; remaproughness
//                       false: alpha = roughness); effectively smooth (both alphas < 1e-3) -> delta Conductor with
//                       the RGB eta + i k, else RoughConductor. "reflectance" r (clamped to [0, 0.9999]) replaces
//                       eta / k by eta = 1, k = 2 sqrt(r) / sqrt(1 - r).
//   * dielectric     -> eta = 1 or effectively smooth: delta Dielectric(eta); else RoughDielectric (reflection and
//                       transmission in the surface part; the material is oriented()).
//   * coateddiffuse  -> CoatedDiffuse (reflectance and albedo clamped to [0, 1]; its smooth coat's mirror
//                       reflection comes from sample() as a specular sample).
//   * coatedconductor -> CoatedConductor: the coat from "interface.*" (eta, roughness as for dielectric), the base
//                       a RoughConductor (smooth or rough, "conductor.*" roughness) whose eta and k, or the eta = 1,
//                       k = 2 sqrt(r) / sqrt(1 - r) of "reflectance", are divided by the coat's eta (pbrt-v4: the
//                       conductor's index relative to the coat); thickness, albedo, g, maxdepth, nsamples as for
//                       coateddiffuse.
//   * diffusetransmission -> DiffuseTransmission(clamp(scale * reflectance), clamp(scale * transmittance)), each
//                       clamped to [0, 1] after scaling as pbrt-v4 does.
//   * thindielectric -> delta ThinDielectric(eta): the thin slab's summed internal reflections, transmission
//                       straight through with no change of medium (the material is not oriented()).
//   * interface      -> passes_through, with a Dielectric(1) pass-through delta for integrators that ignore it.
// Bad pbrt values (negative or non-finite roughness, thickness, colours, scale; eta <= 0; |g| >= 1; maxdepth or
// nsamples out of range) throw kiln::Error naming the file, "Material id=N" and the pbrt material type.
// A mix (MaterialDesc::mix, any format) builds to an empty placeholder: the world picks one of its components at
// each hit (renderer/world/material_mix.h), so the placeholder is never shaded.
//
// Bad input (dangling BRDF index, negative exponent, missing or non-positive refraction index where one is
// needed, negative or non-finite colours) throws kiln::Error naming the scene file and "Material id=N".
#pragma once
#include "materials/material.h"
#include "scenes/scene.h"

namespace kiln {

// Transparency values below this are treated as this (absorption -ln(1e-6) ~ 13.8 per unit length), keeping the
// absorption coefficient finite so that transmittance(0) is 1 and never NaN.
inline constexpr float kMinTransparency = 1e-6f;
// pbrt-v4 clamps a conductor's "reflectance" below 1 (k = 2 sqrt(r) / sqrt(1 - r) is infinite at 1).
inline constexpr float kMaxPbrtConductorReflectance = 0.9999f;
// Limits on coateddiffuse's random walks: every eval() runs nsamples walks of up to maxdepth events, so larger
// values would stall a render rather than change it.
inline constexpr int kMaxPbrtLayeredDepth = 10000;
inline constexpr int kMaxPbrtLayeredSamples = 1024;
// Exponent applied by degamma="true".
inline constexpr float kDegammaExponent = 2.2f;

Material build_material(const MaterialDesc& desc, const SceneDesc& scene);

}  // namespace kiln
