// Clarberg's octahedral equal-area mapping between the unit square and the unit sphere ("Fast Equal-Area Mapping of
// the (Hemi)Sphere using SIMD", 2008), the layout pbrt-v4 uses for spherical cameras and environment maps: equal
// areas of the square map to equal solid angles, the centre to +z, the corners to -z, and the square's edges fold
// onto themselves (octahedral wrap), so that lookups just outside the square continue across the seam.
#pragma once
#include "core/vec.h"

namespace kiln {

inline Vec3f equal_area_square_to_sphere(Vec2f p) {
  const float u = 2.0f * p.x - 1.0f, v = 2.0f * p.y - 1.0f;
  const float up = std::abs(u), vp = std::abs(v);
  // Signed distance from the diamond |u| + |v| = 1 (positive inside: the upper hemisphere); r the radius along it.
  const float signed_distance = 1.0f - (up + vp);
  const float r = 1.0f - std::abs(signed_distance);
  const float phi = (r == 0.0f ? 1.0f : (vp - up) / r + 1.0f) * (kPi / 4.0f);
  const float z = std::copysign(1.0f - r * r, signed_distance);
  const float cos_phi = std::copysign(std::cos(phi), u), sin_phi = std::copysign(std::sin(phi), v);
  const float s = r * safe_sqrt(2.0f - r * r);
  return {cos_phi * s, sin_phi * s, z};
}

// A point just outside [0, 1]^2 to the point of the square it continues into across the folded edge.
inline Vec2f wrap_equal_area_square(Vec2f p) {
  if (p.x < 0.0f) {
    p.x = -p.x;
    p.y = 1.0f - p.y;
  } else if (p.x > 1.0f) {
    p.x = 2.0f - p.x;
    p.y = 1.0f - p.y;
  }
  if (p.y < 0.0f) {
    p.x = 1.0f - p.x;
    p.y = -p.y;
  } else if (p.y > 1.0f) {
    p.x = 1.0f - p.x;
    p.y = 2.0f - p.y;
  }
  return p;
}

}  // namespace kiln
