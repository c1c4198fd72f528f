// The octahedral equal-area mapping (core/equal_area.h): it round-trips both ways, lands on pbrt-v4's orientation
// (centre +z, corners -z, the diamond on the equator), preserves area (uniform points of the square are uniform
// directions: chi-square over the sphere; uniform directions fall into a grid of the square's cells in proportion to
// their area: chi-square over the square), and the octahedral wrap folds a texel beyond an edge onto the texel whose
// directions it continues.
#include "core/equal_area.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "support/chi2.h"

namespace kiln {
namespace {

constexpr int kChi2Tests = 2;
constexpr uint64_t kSamples = 1'000'000;

TEST(EqualArea, SquareToSphereToSquareRoundTrips) {
  Rng rng(1, 2);
  for (int i = 0; i < 200000; ++i) {
    const Vec2f p = rng.next_2d();
    const Vec3f d = equal_area_square_to_sphere(p);
    ASSERT_NEAR(length(d), 1.0f, 2e-6f) << p.x << " " << p.y;
    const Vec2f back = equal_area_sphere_to_square(d);
    ASSERT_NEAR(back.x, p.x, 2e-6f) << p.x << " " << p.y;
    ASSERT_NEAR(back.y, p.y, 2e-6f) << p.x << " " << p.y;
  }
}

TEST(EqualArea, SphereToSquareToSphereRoundTripsAlsoNearThePoles) {
  Rng rng(3, 4);
  for (int i = 0; i < 200000; ++i) {
    const Vec3f d = sample_uniform_sphere(rng.next_2d());
    const Vec2f p = equal_area_sphere_to_square(d);
    ASSERT_TRUE(p.x >= 0.0f && p.x <= 1.0f && p.y >= 0.0f && p.y <= 1.0f);
    const Vec3f back = equal_area_square_to_sphere(p);
    ASSERT_LT(length(back - d), 4e-6f) << d.x << " " << d.y << " " << d.z;
  }
  // A direction 1e-4 rad from each pole keeps that angle (1 - |z| alone would have lost it to rounding).
  for (float sign : {1.0f, -1.0f}) {
    const Vec3f d = normalize(Vec3f(1e-4f, 0.0f, sign));
    const Vec3f back = equal_area_square_to_sphere(equal_area_sphere_to_square(d));
    EXPECT_NEAR(back.x, 1e-4f, 1e-7f);
  }
}

TEST(EqualArea, MatchesPbrtV4sOrientation) {
  const auto near = [](Vec3f a, Vec3f b) { return length(a - b) < 1e-6f; };
  EXPECT_TRUE(near(equal_area_square_to_sphere({0.5f, 0.5f}), {0, 0, 1}));
  for (Vec2f corner : {Vec2f(0, 0), Vec2f(1, 0), Vec2f(0, 1), Vec2f(1, 1)})
    EXPECT_TRUE(near(equal_area_square_to_sphere(corner), {0, 0, -1}));
  EXPECT_TRUE(near(equal_area_square_to_sphere({1.0f, 0.5f}), {1, 0, 0}));
  EXPECT_TRUE(near(equal_area_square_to_sphere({0.5f, 1.0f}), {0, 1, 0}));
  EXPECT_TRUE(near(equal_area_square_to_sphere({0.0f, 0.5f}), {-1, 0, 0}));
  EXPECT_TRUE(near(equal_area_square_to_sphere({0.5f, 0.0f}), {0, -1, 0}));
  // The diamond's edge is the equator: its midpoint in the first quadrant is 45 degrees between +x and +y.
  EXPECT_TRUE(near(equal_area_square_to_sphere({0.75f, 0.75f}), normalize(Vec3f(1, 1, 0))));
}

TEST(EqualArea, UniformSquareIsUniformSphereChi2) {
  const auto r = test::chi2_sphere([](Rng& rng) { return equal_area_square_to_sphere(rng.next_2d()); },
                                   [](Vec3f) { return 1.0 / (4.0 * test::detail::kPiD); }, kSamples, 20, 40, 0.01,
                                   kChi2Tests, 7);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(EqualArea, UniformSphereFillsTheSquaresCellsByAreaChi2) {
  // Cells of the square, at a resolution that does not align with the diamond, each receive uniform directions in
  // proportion to their area: the map preserves area region by region, not only in total.
  constexpr int kCells = 23;
  std::vector<uint64_t> counts(kCells * kCells, 0);
  Rng rng(9, 1);
  for (uint64_t i = 0; i < kSamples; ++i) {
    const Vec2f p = equal_area_sphere_to_square(sample_uniform_sphere(rng.next_2d()));
    const int x = std::clamp(int(p.x * kCells), 0, kCells - 1), y = std::clamp(int(p.y * kCells), 0, kCells - 1);
    ++counts[size_t(y * kCells + x)];
  }
  const std::vector<double> expected(counts.size(), 1.0 / double(counts.size()));
  const auto r = test::chi2_discrete(counts, expected, 0.01, kChi2Tests);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(EqualArea, OctahedralWrapContinuesAcrossEveryEdge) {
  // A direction just outside the square (found by continuing a texel's centre direction across the edge) is covered
  // by the texel the wrap names.
  constexpr int kW = 16;
  for (int i = 0; i < kW; ++i) {
    struct Case {
      int x, y;
    } outside[] = {{-1, i}, {kW, i}, {i, -1}, {i, kW}};
    for (const Case c : outside) {
      int x = c.x, y = c.y;
      wrap_octahedral(x, y, kW, kW);
      // The texel outside the edge, at its centre, mirrored back through the edge, lies in the wrapped texel.
      Vec2f p((float(c.x) + 0.5f) / kW, (float(c.y) + 0.5f) / kW);
      if (p.x < 0.0f || p.x > 1.0f) p = {p.x < 0.0f ? -p.x : 2.0f - p.x, 1.0f - p.y};
      if (p.y < 0.0f || p.y > 1.0f) p = {1.0f - p.x, p.y < 0.0f ? -p.y : 2.0f - p.y};
      EXPECT_EQ(x, int(p.x * kW)) << c.x << " " << c.y;
      EXPECT_EQ(y, int(p.y * kW)) << c.x << " " << c.y;
      // ... and that mirrored point is the same direction as the edge point it continues.
      const Vec2f edge(std::clamp((float(c.x) + 0.5f) / kW, 0.0f, 1.0f), std::clamp((float(c.y) + 0.5f) / kW, 0.0f, 1.0f));
      const Vec2f mirrored_edge = c.x < 0 || c.x >= kW ? Vec2f(edge.x, 1.0f - edge.y) : Vec2f(1.0f - edge.x, edge.y);
      EXPECT_LT(length(equal_area_square_to_sphere(edge) - equal_area_square_to_sphere(mirrored_edge)), 1e-5f);
    }
  }
}

}  // namespace
}  // namespace kiln
