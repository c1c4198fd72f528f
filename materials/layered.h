// The layered BxDF of pbrt-v4 (its LayeredBxDF<DielectricBxDF, Bottom, twoSided = true>): a dielectric coat,
// smooth or rough, over a reflecting base, with an optional scattering and absorbing medium between them.
// Evaluated, sampled and its pdf estimated by a stochastic random walk between the two interfaces (Guo et al. 2018,
// "Position-free Monte Carlo simulation for arbitrary layered BSDFs"). CoatedDiffuse (Lambertian base) and
// CoatedConductor (conductor base) are this walk over their base.
//
// Parameters (shared by both materials):
//   coat         the interface: its eta (inside / outside) and Trowbridge-Reitz roughness; effectively smooth
//                alphas make it a smooth interface (see "Smooth layers" below)
//   base         the bottom layer, one-sided reflection in its own local frame (wo.z > 0): any BxDF with
//                eval / pdf / sample / flags (Lambert, RoughConductor, smooth or rough)
//   thickness    layer thickness in units of the medium's mean free path (sigma_t = 1), > 0; values below
//                FLT_MIN are raised to it. With albedo = 0 the layer still ABSORBS: every crossing at direction w
//                is attenuated by exp(-thickness / |w.z|) (pbrt-v4's behaviour, default 0.01)
//   albedo       single-scattering albedo of the medium in [0, 1]^3; 0 = no scattering, only the absorption above
//   g            Henyey-Greenstein asymmetry of the medium's scattering, in (-1, 1)
//   max_depth    interface / medium events per random walk (pbrt's maxdepth, default 10). The walk is truncated
//                there, so energy that needs more internal bounces is lost: a white diffuse base under a smooth
//                eta = 1.5 coat keeps 1 - r_i^5 ~ 0.92 of the transmitted energy at max_depth 10 (r_i ~ 0.6 is the
//                coat's internal diffuse reflectance), exactly as pbrt-v4 renders it.
//   n_samples    random walks averaged per eval() / pdf() call (pbrt's nsamples, default 1)
// Two-sided: written for wo.z > 0 and mirrored by Material. Reflection only (the base does not transmit).
//
// Determinism: the estimators draw their random numbers from a PCG stream seeded by a hash of their arguments
// (eval: wo, wi; pdf: wo, wi with another salt; sample: wo and the sample's (uc, u)). eval(wo, wi) and pdf(wo, wi)
// are therefore pure functions, and images stay bit-identical for any thread count. Each call is one unbiased
// estimate (eval) or one fixed positive approximation (pdf) of the true value; perturbing an argument by one ulp
// draws an independent estimate.
//
// Exit weights: with a rough coat, eval() reaches wi from a base or medium vertex by two strategies, combined
// with the power heuristic: NEE (the coat sampled from wi, in importance mode, gives the inside direction -w
// with density p_nee = coat.pdf(wi, -w)) and the walk's own next direction w (base or phase-function sample,
// density p_walk) evaluated through the coat. The weights sum to 1 only if both use the same p_nee and p_walk.
// pbrt-v4's f() weights the second strategy with coat.pdf(-w, wi) instead, the density of the OUTSIDE direction
// given w, which differs from p_nee by the refraction Jacobian and eta^2: its f() then overestimates the BSDF,
// e.g. by 4-8% of the albedo for coats with roughness 0.025-0.15 over reflectance 0.2-0.4 (the killeroo scene),
// and no longer agrees with its own Sample_f (mmp/pbrt-v4 issue 187 reports that disagreement). Kiln uses the
// consistent weight; exit_weight = PbrtV4 reproduces pbrt-v4's estimator for side-by-side comparisons.
//
// Smooth layers: a smooth coat's mirror reflection R(theta_o) is a delta lobe. As in pbrt-v4 it is returned only by
// sample(), flagged kLobeSpecular with f = R / cos(theta_i) and pdf = the probability of choosing it (R); eval()
// and pdf() exclude it (an integrator's NEE never sees it, and it never takes part in MIS). The same holds for any
// walk whose every event was specular (a smooth coat over a smooth conductor: the whole BSDF is then a delta lobe
// in the mirror direction). The integrator treats such a sample like any delta bounce (emission found along it is
// counted in full), which keeps MIS correct: a delta path has exactly one strategy, and everything eval() returns
// is shared between NEE and BSDF sampling. NEE through a smooth coat, or towards a smooth base, has no competing
// strategy and weighs 1.
//
// Sampled directions and MIS: the true density of sample()'s directions has no closed form. Every non-specular
// sample reports pdf = pdf(wo, wi), the deterministic estimate, and f = w * pdf / |cos(theta_i)| where w is the
// random walk's exact path weight, so f |cos| / pdf = w (unbiased path throughput) while the reported pdf is the
// same function of (wo, wi) that pdf() returns to NEE. The power-heuristic weights of NEE and BSDF sampling
// therefore sum to 1 for every direction, which is all MIS needs to stay unbiased (pbrt-v4 gets the same effect
// from pdfIsProportional and a second PDF() call). The pdf is 0.1 / (2 pi) + 0.9 x pbrt's single-bounce (TRT)
// estimate over the upper hemisphere, never 0 there, and 0 below.
#pragma once
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/lambert.h"
#include "materials/rough_conductor.h"
#include "materials/rough_dielectric.h"

namespace kiln {

// MIS weight of the walk's exit through a rough coat towards wi (see "Exit weights" above).
enum class LayeredExitWeight {
  Consistent,  // both strategies weighted with the same two densities of the inside direction: unbiased
  PbrtV4,      // pbrt-v4's LayeredBxDF::f: biased high (3-8% for the killeroo's coats), for comparisons with pbrt
};

// What lies above the base: the coat and the medium between coat and base.
struct LayerStack {
  RoughDielectric coat{1.5f, TrowbridgeReitz{}};
  float thickness = 0.01f;
  Rgb albedo{0.0f};
  float g = 0.0f;
  int max_depth = 10;
  int n_samples = 1;
  LayeredExitWeight exit_weight = LayeredExitWeight::Consistent;
};

// Parameters: `layers` (above) and `base`, the bottom layer (Lambert: CoatedDiffuse, RoughConductor:
// CoatedConductor).
template <class Base>
struct Layered {
  LayerStack layers;
  Base base;

  Rgb eval(Vec3f wo, Vec3f wi) const;
  float pdf(Vec3f wo, Vec3f wi) const;
  std::optional<BsdfSample> sample(Vec3f wo, float uc, Vec2f u) const;
  // Reflection; specular when the coat is; diffuse when the base or the medium scatters diffusely; glossy when
  // either interface is rough. Both layers smooth without a medium: specular alone (a delta lobe).
  uint32_t flags() const;
  // Coat reflectance at normal incidence plus the base's albedo estimate seen through the coat.
  float albedo_estimate() const;
};

extern template struct Layered<Lambert>;
extern template struct Layered<RoughConductor>;

}  // namespace kiln
