// Sums of octaves of Kiln's Perlin noise (core/perlin.h) for pbrt-v4's noise textures (fbm, wrinkled,
// windy, marble). Octave i is the noise at frequency 1.99^i with amplitude omega^i (1.99 rather than 2, so that the
// octaves' lattices never line up). Octaves finer than the footprint can resolve are left out: with the footprint's
// larger side len (the change of the point per pixel step), octave i is sampled about 2^i len apart, and aliases
// once that exceeds half its period, i.e. from i = -1 - log2(len) on. That octave count n is fractional: the last
// octave fades in with a smoothstep of n's fraction over [0.3, 0.7]. A zero footprint sums all octaves.
#pragma once
#include "core/vec.h"

namespace kiln {

// Fractional Brownian motion: sum of omega^i n(1.99^i p), in about [-1, 1] / (1 - omega).
float fbm(Vec3f p, Vec3f dpdx, Vec3f dpdy, float omega, int max_octaves);
// Turbulence: the same sum of |n|; octaves the footprint cannot resolve count as their average, 0.2 omega^i.
float turbulence(Vec3f p, Vec3f dpdx, Vec3f dpdy, float omega, int max_octaves);

// The average of |n| over space that turbulence substitutes for unresolved octaves.
inline constexpr float kAverageAbsNoise = 0.2f;

}  // namespace kiln
