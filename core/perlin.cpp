#include "core/perlin.h"

#include <cmath>

namespace kiln {
namespace {

constexpr int kGradients = 16;
constexpr float kG[kGradients][3] = {{1, 1, 0},  {-1, 1, 0},  {1, -1, 0}, {-1, -1, 0}, {1, 0, 1},  {-1, 0, 1},
                                     {1, 0, -1}, {-1, 0, -1}, {0, 1, 1},  {0, -1, 1},  {0, 1, -1}, {0, -1, -1},
                                     {1, 1, 0},  {-1, 1, 0},  {0, -1, 1}, {0, -1, -1}};

int phi(long long i) {
  const long long m = ((i % kGradients) + kGradients) % kGradients;
  return kCoursePerlinPermutation[size_t(m)];
}

float weight(float t) {
  const float a = std::fabs(t);
  if (a >= 1.0f) return 0.0f;
  const float a3 = a * a * a;
  return 1.0f - 10.0f * a3 + 15.0f * a3 * a - 6.0f * a3 * a * a;
}

}  // namespace

float course_perlin(Vec3f p) {
  // The lattice's gradients repeat every kGradients cells along each axis: fmod (exact) moves p by whole periods,
  // which leaves every offset from a lattice point bit for bit as it was, and keeps far points (fractal noise's fine
  // octaves) within the range of the lattice's integers.
  if (!is_finite(p)) return 0.0f;
  for (int a = 0; a < 3; ++a) p[a] = std::fmod(p[a], float(kGradients));
  const long long x0 = (long long)std::floor(p.x), y0 = (long long)std::floor(p.y), z0 = (long long)std::floor(p.z);
  float n = 0.0f;
  for (int dx = 0; dx <= 1; ++dx)
    for (int dy = 0; dy <= 1; ++dy)
      for (int dz = 0; dz <= 1; ++dz) {
        const long long i = x0 + dx, j = y0 + dy, k = z0 + dz;
        const float vx = p.x - float(i), vy = p.y - float(j), vz = p.z - float(k);
        const float* g = kG[phi(i + phi(j + phi(k)))];
        n += (g[0] * vx + g[1] * vy + g[2] * vz) * weight(vx) * weight(vy) * weight(vz);
      }
  return n;
}

Vec3f course_perlin_gradient(Vec3f p) {
  const float h = kPerlinGradientStep;
  const auto d = [&](Vec3f e) { return (course_perlin(p + e) - course_perlin(p - e)) / (2.0f * h); };
  return {d({h, 0, 0}), d({0, h, 0}), d({0, 0, h})};
}

}  // namespace kiln
