// Perlin gradient noise as the CENG795 course defines it (homework 4, 2019; README "Textures"):
//   * 16 gradients G: the 12 edge directions of a cube, (+-1, +-1, 0), (+-1, 0, +-1), (0, +-1, +-1), followed by
//     (1, 1, 0), (-1, 1, 0), (0, -1, 1), (0, -1, -1) (so that a 4-bit index picks them evenly);
//   * a permutation table P of 0..15, phi(i) = P[i mod 16] (mod taken non-negative), and the gradient of lattice
//     point (i, j, k) is G[phi(i + phi(j + phi(k)))];
//   * weight f(t) = 1 - 10|t|^3 + 15|t|^4 - 6|t|^5 for |t| < 1 (0 beyond);
//   * n(p) = sum over the 8 lattice corners c of the cell holding p of (G_c . (p - c)) f(px - cx) f(py - cy) f(pz - cz).
// The course leaves P a random permutation; Kiln fixes the one below so renders are reproducible.
// The gradients and the weight are those of pbrt-v4's noise (Perlin's improved noise), whose permutation has 256
// entries: pbrt's textures (renderer/texture/) and its "cloud" medium (media/) built on it have pbrt's kind of
// pattern, not pbrt's exact one.
#pragma once
#include <array>

#include "core/vec.h"

namespace kiln {

inline constexpr std::array<int, 16> kCoursePerlinPermutation = {11, 2, 14, 7, 0, 9, 4, 13, 6, 1, 15, 10, 3, 12, 8, 5};

// n(p), in about [-1, 1].
float course_perlin(Vec3f p);
// The gradient of n at p (central differences of step kPerlinGradientStep in noise space).
Vec3f course_perlin_gradient(Vec3f p);
inline constexpr float kPerlinGradientStep = 1e-3f;

// Frequency ratio between the octaves of sums of noise (pbrt-v4's textures and cloud): 1.99 rather than 2, so that
// the octaves' lattices never line up.
inline constexpr float kOctaveLacunarity = 1.99f;

}  // namespace kiln
