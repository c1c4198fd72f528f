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

struct BsdfSample {
  Rgb f;            // BRDF value for (wo, wi); for specular lobes f already holds weight / |cos theta_i| so that
                    // f * |cos theta_i| / pdf is the path weight, uniformly for every lobe
  Vec3f wi;         // local shading frame
  float pdf = 0;    // solid-angle pdf; for specular lobes the discrete probability of choosing that lobe
  uint32_t flags = kLobeNone;
  float eta = 1.0f;  // relative IOR crossed (transmission only)
  bool is_specular() const { return (flags & kLobeSpecular) != 0; }
  bool is_transmission() const { return (flags & kLobeTransmission) != 0; }
};

}  // namespace kiln
