// Clarberg's octahedral equal-area mapping between the unit square and the unit sphere (P. Clarberg, "Fast
// Equal-Area Mapping of the (Hemi)Sphere using SIMD", JGT 2008), in the orientation pbrt-v4 stores environment maps
// with: the square's centre is +z, its four corners -z, the diamond |u - 1/2| + |v - 1/2| = 1/2 the equator; u grows
// towards +x and v towards +y. Any region of the square maps onto a region of 4 pi times its area, so a density p
// over the square is the solid-angle density p / (4 pi) on the sphere.
//
// Construction, on (a, b) = (2u - 1, 2v - 1) in [-1, 1]^2 folded into the first quadrant (|a|, |b|): the distance
// r = 1 - |1 - |a| - |b|| from the nearest pole's point (centre or corner) fixes z = +-(1 - r^2) (Lambert's
// equal-area projection of a disk of radius r), and the position along the diamond's edge |a| + |b| = r (or its
// mirror image in the outer triangle) fixes phi in [0, pi / 2], linearly; the signs of a and b choose the quadrant.
#pragma once
#include "core/math.h"
#include "core/vec.h"

namespace kiln {

inline Vec3f equal_area_square_to_sphere(Vec2f p) {
  const float a = 2.0f * p.x - 1.0f, b = 2.0f * p.y - 1.0f;
  const float abs_a = std::abs(a), abs_b = std::abs(b);
  const float to_equator = 1.0f - (abs_a + abs_b);  // > 0: inner diamond (z > 0)
  const float r = 1.0f - std::abs(to_equator);
  const float phi = r > 0.0f ? (kPi / 4.0f) * ((abs_b - abs_a) / r + 1.0f) : 0.0f;
  const float z = std::copysign(1.0f - r * r, to_equator);
  const float ring = r * safe_sqrt(2.0f - r * r);  // sqrt(1 - z^2)
  return {std::copysign(std::cos(phi), a) * ring, std::copysign(std::sin(phi), b) * ring, z};
}

// d must be of unit length.
inline Vec2f equal_area_sphere_to_square(Vec3f d) {
  const float x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
  // r^2 = 1 - |z| computed as (x^2 + y^2) / (1 + |z|), which keeps its precision near the poles.
  const float r = std::sqrt((x * x + y * y) / (1.0f + z));
  const float phi = std::atan2(y, x);  // [0, pi / 2]
  float b = r * phi * (2.0f / kPi);
  float a = r - b;
  if (d.z < 0.0f) {  // the outer triangle: mirror across the diamond's edge
    const float a_in = a;
    a = 1.0f - b;
    b = 1.0f - a_in;
  }
  a = std::copysign(a, d.x);
  b = std::copysign(b, d.y);
  return {0.5f * (a + 1.0f), 0.5f * (b + 1.0f)};
}

// A texel index (x, y) just outside a w x h equal-area image, folded back onto the texel that covers the same
// directions: the square's edges are creased in half (a point of the edge and its mirror image across the edge's
// midpoint are the same direction), so crossing the left or right edge mirrors the row, crossing the top or bottom
// edge mirrors the column (pbrt-v4's "octahedralsphere" wrap). Indices at most one image beyond an edge.
inline void wrap_octahedral(int& x, int& y, int w, int h) {
  if (x < 0 || x >= w) {
    x = x < 0 ? -1 - x : 2 * w - 1 - x;
    y = h - 1 - y;
  }
  if (y < 0 || y >= h) {
    y = y < 0 ? -1 - y : 2 * h - 1 - y;
    x = w - 1 - x;
  }
  x = std::clamp(x, 0, w - 1);
  y = std::clamp(y, 0, h - 1);
}

}  // namespace kiln
