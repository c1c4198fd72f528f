// One deterministic outcome of a delta BSDF for a given wo: the direction, the radiance weight it carries and
// the probability with which sampling picks it.
#pragma once
#include "core/color.h"
#include "core/vec.h"

namespace kiln {

struct SpecularBranch {
  Vec3f wi;                  // local frame
  Rgb weight;                // multiplies the radiance arriving along wi (no cosine, no pdf)
  float probability = 1.0f;  // chance that sample() picks this branch (branch probabilities sum to 1)
  bool transmission = false;
  float etap = 1.0f;  // relative IOR crossed (transmission only)
};

}  // namespace kiln
