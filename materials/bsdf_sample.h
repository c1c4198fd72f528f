// Sampling record shared by every BRDF (pbrt-v4 style: a value, not an out-parameter soup).
#pragma once
#include <cstdint>

#include "core/color.h"
#include "core/vec.h"

namespace kiln {

enum LobeFlags : uint32_t {
  kLobeNone = 0,
  kLobeReflection = 1u << 0,
  kLobeTransmission = 1u << 1,
  kLobeDiffuse = 1u << 2,
  kLobeGlossy = 1u << 3,
  kLobeSpecular = 1u << 4,  // delta (or, for Roughness-perturbed mirrors, a direction with no evaluable pdf)
};

// Which end of a path wo faces (pbrt's TransportMode). Radiance: wo leads towards the camera, the BSDF carries
// radiance from wi to wo and refraction scales it by 1/etap^2. Importance: the adjoint (wo leads towards a
// light), no scaling; f_importance(wo, wi) = f_radiance(wi, wo). Materials are evaluated in Radiance mode; the
// layered BxDF needs both for its internal random walk.
enum class Transport { Radiance, Importance };

// Lobe subsets a sampler may be restricted to (pbrt's BxDFReflTransFlags): reflection, transmission or both.
inline constexpr uint32_t kSampleAll = kLobeReflection | kLobeTransmission;

struct BsdfSample {
  Rgb f;            // BRDF value for (wo, wi); for specular lobes f already holds weight / |cos theta_i| so that
                    // f * |cos theta_i| / pdf is the path weight, uniformly for every lobe. Stochastic lobes
                    // (CoatedDiffuse) report pdf = their pdf(wo, wi) and f = path weight * pdf / |cos theta_i|, an
                    // estimate of the BSDF along the sampled internal path rather than eval(wo, wi).
  Vec3f wi;         // local shading frame
  float pdf = 0;    // solid-angle pdf; for specular lobes the discrete probability of choosing that lobe
  uint32_t flags = kLobeNone;
  float eta = 1.0f;  // relative IOR crossed (transmission only)
  bool is_specular() const { return (flags & kLobeSpecular) != 0; }
  bool is_transmission() const { return (flags & kLobeTransmission) != 0; }
};

}  // namespace kiln
