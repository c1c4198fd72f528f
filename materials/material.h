// A built material: a non-delta surface BSDF (diffuse / glossy, possibly none) plus an optional delta part
// (mirror, dielectric, conductor, optionally roughened). All directions are in the local shading frame
// (cos theta = w.z, wo and the geometric side on +z unless transmission is involved).
//
// Surface BSDFs are written one-sided for wo.z > 0 and mirrored by Material, except those that declare
// `static constexpr bool kHandlesBothSides = true` (RoughDielectric): they transmit, are not symmetric in eta, and
// take wo on either side as it is. A material holding one is oriented(): its +z must be the geometric outside.
#pragma once
#include <optional>
#include <string>
#include <variant>

#include "materials/bsdf_sample.h"
#include "materials/blinn_phong.h"
#include "materials/coated_conductor.h"
#include "materials/coated_diffuse.h"
#include "materials/conductor.h"
#include "materials/dielectric.h"
#include "materials/diffuse_transmission.h"
#include "materials/lambert.h"
#include "materials/mirror.h"
#include "materials/perturb.h"
#include "materials/phong.h"
#include "materials/rough_conductor.h"
#include "materials/rough_dielectric.h"
#include "materials/thin_dielectric.h"
#include "materials/torrance_sparrow.h"

namespace kiln {

struct NoSurface {};
using SurfaceBrdf = std::variant<NoSurface, Lambert, Phong, BlinnPhong, TorranceSparrow, RoughConductor,
                                 RoughDielectric, CoatedDiffuse, CoatedConductor, DiffuseTransmission>;
struct NoDelta {};
using DeltaBsdf = std::variant<NoDelta, Mirror, Dielectric, Conductor, ThinDielectric>;

// One deterministic branch of a delta lobe for the Whitted-style tracer (reflection and refraction).
struct DeltaBranch {
  Vec3f wi;       // local frame
  Rgb weight;     // multiplies the radiance arriving along wi (Fresnel, mirror colour; no cosine, no pdf)
  bool transmission = false;
  float etap = 1.0f;  // relative IOR crossed (transmission only): weight includes the 1/etap^2 radiance scaling
};

struct Material {
  Rgb ambient{0};
  SurfaceBrdf surface = NoSurface{};
  DeltaBsdf delta = NoDelta{};
  float roughness = 0.0f;  // course glossy reflection: perturb delta directions by roughness * U[-0.5,0.5]^2
  Rgb absorption{0};       // Beer-Lambert coefficient inside dielectrics: transmittance exp(-absorption * d)
  // No surface at all (pbrt's "interface" material, a boundary between media): integrators should continue the
  // ray unchanged without counting a bounce. delta then holds Dielectric{1}, a pure pass-through, so that an
  // integrator unaware of the flag still renders it right (at the cost of one bounce of depth).
  bool passes_through = false;

  bool has_surface() const { return !std::holds_alternative<NoSurface>(surface); }
  bool has_delta() const { return !std::holds_alternative<NoDelta>(delta); }
  uint32_t flags() const;
  uint32_t surface_flags() const;  // the non-delta part's lobes (kLobeSpecular: it can return delta samples)
  // The frame's +z must be the geometric outside (delta Dielectric, or a surface BSDF that handles both sides):
  // integrators must not flip such a frame towards wo.
  bool oriented() const;
  // sample() reads uc: there is a delta part to choose, or a surface BSDF that chooses among its lobes. A BSDF
  // with one lobe declares `static constexpr bool kIgnoresLobeChoice = true`, and integrators then need not draw
  // uc (the sampler's hashing is a tenth of a diffuse scene's render time).
  bool reads_lobe_choice() const;
  // The non-delta part transmits (RoughDielectric, DiffuseTransmission): next event estimation must also try
  // light directions on the other side of the surface, and a transmitted sample crosses to the other side (into
  // the inside for an oriented material; a thin sheet has no inside and changes no medium).
  bool has_surface_transmission() const { return (surface_flags() & kLobeTransmission) != 0; }

  // Non-delta part only (the delta part, and delta lobes of the surface part such as a smooth coat's mirror
  // reflection, evaluate to 0 for any pair of directions).
  Rgb eval(Vec3f wo, Vec3f wi) const;
  // pdf of sample() producing wi through its non-delta lobes, including the lobe-selection probability.
  float pdf(Vec3f wo, Vec3f wi) const;
  // Samples the whole material (surface and delta lobes). uc chooses the lobe, u the direction.
  // Empty when no direction could be produced; never NaN. A surface part may return specular samples too
  // (CoatedDiffuse's smooth coat): integrators must look at the sample's flags, not at which part produced it.
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  // Samples the surface (non-delta) part alone; the pdf does NOT include 1 - delta_probability. For integrators
  // that follow the delta part deterministically (the course's Fresnel split). Empty without a surface part.
  std::optional<BsdfSample> sample_surface(Vec3f wo, float uc, Vec2f u) const;
  float pdf_surface(Vec3f wo, Vec3f wi) const;  // sample_surface's pdf
  // Probability that sample() picks the delta part: 1 with no surface BRDF, 0 with no delta part, otherwise the
  // documented mixture weight. Integrators that sample the surface part their own way (uniform / cosine) use it to
  // choose between the parts.
  float delta_probability(Vec3f wo) const;
  // Samples the delta part only (mirror / dielectric / conductor, roughened when roughness > 0); the returned pdf
  // does NOT include delta_probability. Empty when there is no delta part.
  std::optional<BsdfSample> sample_delta(Vec3f wo, float uc, Vec2f u) const;
  // The delta part's deterministic branches (0, 1 or 2), for the course ray tracer; roughness is applied by
  // the caller through perturb(). Returns the count written to out.
  int delta_branches(Vec3f wo, DeltaBranch out[2]) const;
  Rgb transmittance(float distance) const { return exp(absorption * (-distance)); }
  // What the material compiled to, e.g. "lambert", "blinn-phong(original)+mirror", "dielectric" (kiln --stats).
  std::string describe() const;
};

}  // namespace kiln
