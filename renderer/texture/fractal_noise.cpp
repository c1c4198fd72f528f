#include "renderer/texture/fractal_noise.h"

#include <algorithm>
#include <cmath>

#include "core/perlin.h"

namespace kiln {
namespace {

float smooth_step(float x, float a, float b) {
  const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// How many octaves the footprint resolves (see the header), in [0, max_octaves].
float resolved_octaves(Vec3f dpdx, Vec3f dpdy, int max_octaves) {
  const float len2 = std::max(length_squared(dpdx), length_squared(dpdy));
  if (!(len2 > 0.0f)) return float(max_octaves);
  return std::clamp(-1.0f - 0.5f * std::log2(len2), 0.0f, float(max_octaves));
}

}  // namespace

float fbm(Vec3f p, Vec3f dpdx, Vec3f dpdy, float omega, int max_octaves) {
  const float n = resolved_octaves(dpdx, dpdy, max_octaves);
  const int whole = int(std::floor(n));
  float sum = 0.0f, frequency = 1.0f, amplitude = 1.0f;
  for (int i = 0; i < whole; ++i) {
    sum += amplitude * course_perlin(p * frequency);
    frequency *= kOctaveLacunarity;
    amplitude *= omega;
  }
  return sum + amplitude * smooth_step(n - float(whole), 0.3f, 0.7f) * course_perlin(p * frequency);
}

float turbulence(Vec3f p, Vec3f dpdx, Vec3f dpdy, float omega, int max_octaves) {
  const float n = resolved_octaves(dpdx, dpdy, max_octaves);
  const int whole = int(std::floor(n));
  float sum = 0.0f, frequency = 1.0f, amplitude = 1.0f;
  for (int i = 0; i < whole; ++i) {
    sum += amplitude * std::fabs(course_perlin(p * frequency));
    frequency *= kOctaveLacunarity;
    amplitude *= omega;
  }
  // The partial octave blends from the average towards its value; then every octave from it on adds the average
  // (pbrt-v4's definition: the partial octave's average is counted there too).
  const float w = smooth_step(n - float(whole), 0.3f, 0.7f);
  sum += amplitude * ((1.0f - w) * kAverageAbsNoise + w * std::fabs(course_perlin(p * frequency)));
  for (int i = whole; i < max_octaves; ++i) {
    sum += amplitude * kAverageAbsNoise;
    amplitude *= omega;
  }
  return sum;
}

}  // namespace kiln
