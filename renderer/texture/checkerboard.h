// The course's 3-D checkerboard (spec §8; the homework's definition): with c(x) = int((x + Offset) * Scale) mod 2,
// truncated towards zero as C does (so the cell around 0 is twice as wide), the point is white where
// (c(x) xor c(y)) == c(z) and black elsewhere. Evaluated at the hit point in the object's own space.
#pragma once
#include <cmath>

#include "core/vec.h"

namespace kiln {

inline bool checker_odd(float x, float offset, float scale) {
  const double cell = std::trunc(double(x + offset) * double(scale));
  return std::fmod(cell, 2.0) != 0.0;
}

inline bool checkerboard_is_white(Vec3f p, float offset, float scale) {
  const bool x = checker_odd(p.x, offset, scale), y = checker_odd(p.y, offset, scale),
             z = checker_odd(p.z, offset, scale);
  return (x != y) == z;
}

}  // namespace kiln
