// Kiln's Perlin noise (core/perlin.h) against the course's definition written out again here, in double precision.
#include "core/perlin.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kiln {
namespace {

double spec_weight(double t) {
  t = std::fabs(t);
  return t < 1 ? -6 * std::pow(t, 5) + 15 * std::pow(t, 4) - 10 * std::pow(t, 3) + 1 : 0;
}

double spec_perlin(double x, double y, double z) {
  static const int g[16][3] = {{1, 1, 0},  {-1, 1, 0},  {1, -1, 0}, {-1, -1, 0}, {1, 0, 1},  {-1, 0, 1},
                               {1, 0, -1}, {-1, 0, -1}, {0, 1, 1},  {0, -1, 1},  {0, 1, -1}, {0, -1, -1},
                               {1, 1, 0},  {-1, 1, 0},  {0, -1, 1}, {0, -1, -1}};
  const auto phi = [](long i) { return kCoursePerlinPermutation[size_t(((i % 16) + 16) % 16)]; };
  double n = 0;
  for (long i = long(std::floor(x)); i <= long(std::floor(x)) + 1; ++i)
    for (long j = long(std::floor(y)); j <= long(std::floor(y)) + 1; ++j)
      for (long k = long(std::floor(z)); k <= long(std::floor(z)) + 1; ++k) {
        const int* G = g[phi(i + phi(j + phi(k)))];
        const double vx = x - double(i), vy = y - double(j), vz = z - double(k);
        n += (G[0] * vx + G[1] * vy + G[2] * vz) * spec_weight(vx) * spec_weight(vy) * spec_weight(vz);
      }
  return n;
}

TEST(CoursePerlin, MatchesTheSpecFormulaAtFixedPoints) {
  const Vec3f points[] = {{0.3f, 0.7f, 0.1f}, {1.25f, -2.5f, 3.75f}, {-0.6f, -0.2f, -7.9f}, {12.1f, 5.5f, -3.3f},
                          {100.37f, -41.2f, 8.8f}};
  for (const Vec3f& p : points)
    EXPECT_NEAR(course_perlin(p), spec_perlin(p.x, p.y, p.z), 2e-6) << p.x << " " << p.y << " " << p.z;
  // Every lattice point is a zero of the noise (its own gradient sees v = 0, the others have weight 0).
  EXPECT_EQ(course_perlin({3, -2, 5}), 0.0f);
}

TEST(CoursePerlin, GradientIsTheFormulasDerivative) {
  const Vec3f p(0.37f, 1.61f, -2.23f);
  const Vec3f g = course_perlin_gradient(p);
  const double h = 1e-5;
  EXPECT_NEAR(g.x, (spec_perlin(p.x + h, p.y, p.z) - spec_perlin(p.x - h, p.y, p.z)) / (2 * h), 2e-3);
  EXPECT_NEAR(g.y, (spec_perlin(p.x, p.y + h, p.z) - spec_perlin(p.x, p.y - h, p.z)) / (2 * h), 2e-3);
  EXPECT_NEAR(g.z, (spec_perlin(p.x, p.y, p.z + h) - spec_perlin(p.x, p.y, p.z - h)) / (2 * h), 2e-3);
}

}  // namespace
}  // namespace kiln
