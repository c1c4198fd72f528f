// Majorants must bound the extinction wherever a ray can sample it, and the DDA must hand out the ray's part
// inside the box as contiguous segments in order.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "media/majorant_check.h"
#include "media/medium.h"

namespace kiln::test {
namespace {

// A 5x3x4 lattice of values in [0, 4), p0 p1 and an oblique transform: nothing lines up with the axes.
SampledGrid<float> random_lattice(int nx, int ny, int nz, uint64_t seed) {
  Rng rng(seed, 1);
  std::vector<float> v(size_t(nx) * size_t(ny) * size_t(nz));
  for (float& x : v) x = rng.next_float() < 0.3f ? 0.0f : 4.0f * rng.next_float();
  return SampledGrid<float>(std::move(v), nx, ny, nz);
}

Transform oblique() {
  return Transform::translate({0.3f, -0.2f, 0.5f}) * Transform::rotate(35.0f, {1, 2, 0.5f}) *
         Transform::scale({1.5f, 0.7f, 1.2f});
}

Ray random_ray(Rng& rng) {
  const Vec3f o(4.0f * rng.next_float() - 2.0f, 4.0f * rng.next_float() - 2.0f, 4.0f * rng.next_float() - 2.0f);
  const Vec3f target(rng.next_float() * 2.0f - 0.5f, rng.next_float() * 2.0f - 0.5f, rng.next_float() * 2.0f - 0.5f);
  return Ray{o, normalize(target - o)};
}

TEST(SampledGrid, SamplesSitAtCellCentresAndFadeOutside) {
  const SampledGrid<float> g({1, 2, 3, 4, 5, 6, 7, 8}, 2, 2, 2);
  EXPECT_FLOAT_EQ(g.lookup({0.25f, 0.25f, 0.25f}), 1.0f);
  EXPECT_FLOAT_EQ(g.lookup({0.75f, 0.75f, 0.75f}), 8.0f);
  EXPECT_FLOAT_EQ(g.lookup({0.75f, 0.25f, 0.25f}), 2.0f);  // x fastest
  EXPECT_FLOAT_EQ(g.lookup({0.5f, 0.25f, 0.25f}), 1.5f);
  // At a face the lattice blends with the zero beyond it; past half a voxel there is nothing.
  EXPECT_FLOAT_EQ(g.lookup({0.0f, 0.25f, 0.25f}), 0.5f);
  EXPECT_EQ(g.lookup({-0.3f, 0.25f, 0.25f}), 0.0f);
  EXPECT_EQ(g.lookup({0.5f, 1.3f, 0.5f}), 0.0f);
}

TEST(MajorantGrid, BoundsTheDensityEverywhereAlongRays) {
  const GridMedium m(oblique(), Bounds3f({-0.5f, 0, 0}, {1, 1.5f, 0.8f}), Rgb(0.5f, 1, 2), Rgb(1, 0.2f, 0), 0.0f,
                     random_lattice(5, 3, 4, 11), GridEmission{});
  Rng rng(5, 5);
  MajorantCheck check;
  for (int i = 0; i < 2000; ++i) check_majorants(m, random_ray(rng), 10.0f, 8, check);
  EXPECT_EQ(check.worst_excess, 0.0f) << "at " << check.worst_at.x << " " << check.worst_at.y << " " << check.worst_at.z;
  EXPECT_GT(check.points, 10000);
}

TEST(MajorantGrid, DdaSegmentsAreContiguousAndCoverTheBox) {
  const GridMedium m(oblique(), Bounds3f({0, 0, 0}, {1, 1, 1}), Rgb(1.0f), Rgb(0.0f), 0.0f, random_lattice(7, 6, 5, 3),
                     GridEmission{});
  Rng rng(8, 2);
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const Ray ray = random_ray(rng);
    auto segs = m.majorants(ray, 100.0f);
    MajorantSegment s;
    float prev_end = -1.0f, first = -1.0f;
    int n = 0;
    while (segs.next(s)) {
      ASSERT_LE(s.t0, s.t1);
      if (n++ == 0) first = s.t0;
      else ASSERT_FLOAT_EQ(s.t0, prev_end);
      prev_end = s.t1;
      ASSERT_LE(n, 7 + 6 + 5 + 1) << "a ray crosses at most res_x + res_y + res_z voxels";
    }
    if (n == 0) continue;
    ++hits;
    EXPECT_GE(first, 0.0f);
    EXPECT_LE(prev_end, 100.0f);
  }
  EXPECT_GT(hits, 1000);
}

TEST(MediumBox, ClipsRaysToTheTransformedBox) {
  const MediumBox box(oblique(), Bounds3f({-0.5f, 0, 0}, {1, 1.5f, 0.8f}));
  const auto inside = [&](Vec3f p) {
    const Vec3f u = box.unit_point(p);
    return u.x >= 0 && u.x <= 1 && u.y >= 0 && u.y <= 1 && u.z >= 0 && u.z <= 1;
  };
  Rng rng(4, 4);
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const Ray ray = random_ray(rng);
    Vec3f o, d;
    float t0, t1;
    const bool hit = box.clip(ray, 50.0f, o, d, t0, t1);
    // Brute force: where along the ray points are inside.
    float lo = kInfinity, hi = -kInfinity;
    for (int k = 0; k <= 4000; ++k) {
      const float t = 50.0f * float(k) / 4000.0f;
      if (inside(ray.at(t))) lo = std::min(lo, t), hi = std::max(hi, t);
    }
    if (!hit) {
      EXPECT_GT(lo, hi) << "ray " << i << " misses but passes through the box";
      continue;
    }
    ++hits;
    EXPECT_TRUE(inside(ray.at(0.5f * (t0 + t1))));
    if (lo <= hi) {
      EXPECT_NEAR(t0, lo, 0.02f);
      EXPECT_NEAR(t1, hi, 0.02f);
    }
  }
  EXPECT_GT(hits, 500);
}

// Random lattices with every channel in use, and lattices where one channel holds all the density (so that the
// majorant, a maximum over the channels, is tight and must reach every sample that interpolation reads).
TEST(MajorantGrid, RgbGridBoundsEveryChannel) {
  Rng rng(2, 9);
  for (const Rgb& spread : {Rgb(1.0f, 3.0f, 0.1f), Rgb(0.0f, 2.0f, 0.0f)}) {
    std::vector<Rgb> a(60), s(60);
    for (Rgb& c : a) c = spread * Rgb(rng.next_float(), rng.next_float(), rng.next_float());
    for (Rgb& c : s) c = spread * Rgb(rng.next_float(), 0.0f, rng.next_float());
    const RgbGridMedium m(oblique(), Bounds3f({0, 0, 0}, {1, 1, 1}), SampledGrid<Rgb>(a, 5, 4, 3),
                          SampledGrid<Rgb>(s, 5, 4, 3), 2.0f, {}, 1.0f, 0.0f);
    MajorantCheck check;
    for (int i = 0; i < 1000; ++i) check_majorants(m, random_ray(rng), 10.0f, 4, check);
    EXPECT_EQ(check.worst_excess, 0.0f) << "spread " << spread.r << " " << spread.g << " " << spread.b;
    EXPECT_GT(check.points, 1000);
  }
}

// The cloud's one majorant, sigma_a + sigma_s over the ray's part inside its box, bounds its extinction everywhere
// along random rays; rays that miss the box get no segment.
TEST(CloudMedium, MajorantBoundsTheExtinctionAlongRays) {
  const CloudMedium m(oblique(), Bounds3f({-0.5f, -0.3f, 0.0f}, {1.0f, 1.0f, 0.8f}), Rgb(0.2f, 0.0f, 1.0f),
                      Rgb(3.0f, 1.0f, 0.5f), 0.0f, CloudShape{3.0f, 2.0f, 4.0f});
  Rng rng(21, 4);
  MajorantCheck check;
  int missed = 0;
  for (int i = 0; i < 300; ++i) {
    const Ray ray = random_ray(rng);
    auto segs = m.majorants(ray, 10.0f);
    MajorantSegment s;
    missed += !segs.next(s);
    check_majorants(m, ray, 10.0f, 400, check);
  }
  EXPECT_GT(check.points, 30000);
  EXPECT_GT(missed, 0);
  EXPECT_EQ(check.worst_excess, 0.0f) << "at " << check.worst_at.x << " " << check.worst_at.y << " " << check.worst_at.z;
}

}  // namespace
}  // namespace kiln::test
