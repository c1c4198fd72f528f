#include "renderer/accel/triangle_intersect.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "core/transform.h"

namespace kiln {
namespace {

bool hit(const Ray& r, Vec3f a, Vec3f b, Vec3f c, TriangleHit& th) {
  return intersect_triangle(make_watertight_ray(r), a, b, c, r.tmin, r.tmax, th);
}

TEST(TriangleIntersect, AnalyticHitAndBarycentrics) {
  const Vec3f a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  TriangleHit th;
  ASSERT_TRUE(hit(Ray{Vec3f(0.25f, 0.5f, 2), Vec3f(0, 0, -1)}, a, b, c, th));
  EXPECT_FLOAT_EQ(th.t, 2.0f);
  EXPECT_FLOAT_EQ(th.b1, 0.25f);
  EXPECT_FLOAT_EQ(th.b2, 0.5f);
  // Both facings hit (no culling); unnormalised directions scale t.
  ASSERT_TRUE(hit(Ray{Vec3f(0.25f, 0.5f, -2), Vec3f(0, 0, 4)}, a, b, c, th));
  EXPECT_FLOAT_EQ(th.t, 0.5f);
  EXPECT_FALSE(hit(Ray{Vec3f(0.75f, 0.5f, 2), Vec3f(0, 0, -1)}, a, b, c, th)) << "outside the hypotenuse";
  EXPECT_FALSE(hit(Ray{Vec3f(0.25f, 0.5f, 2), Vec3f(0, 0, 1)}, a, b, c, th)) << "behind the origin";
  EXPECT_TRUE(hit(Ray{Vec3f(0.25f, 0.5f, 2), Vec3f(0, 0, -1), 2.0f, 2.0f}, a, b, c, th)) << "[tmin, tmax] inclusive";
  EXPECT_FALSE(hit(Ray{Vec3f(0.25f, 0.5f, 2), Vec3f(0, 0, -1), 0.0f, 1.99f}, a, b, c, th));
  EXPECT_FALSE(hit(Ray{Vec3f(0.25f, 0.5f, 2), Vec3f(0, 0, -1), 2.01f, kInfinity}, a, b, c, th));
  EXPECT_FALSE(hit(Ray{Vec3f(0.25f, 0.5f, 0), Vec3f(1, 0, 0)}, a, b, c, th)) << "ray in the triangle's plane";
  EXPECT_FALSE(hit(Ray{Vec3f(0.25f, 0.5f, 2), Vec3f(0, 0, -1)}, a, b, a, th)) << "degenerate triangle";
}

// A jittered, rotated planar grid of triangles sharing vertices: rays aimed exactly at shared edges and vertices
// must hit at least one of the triangles that meet there. (Planar so that no edge is a silhouette, where a ray
// may legitimately pass on the outside.)
TEST(TriangleIntersect, WatertightOnSharedEdgesAndVertices) {
  constexpr int kN = 8;
  Rng rng(3, 1);
  const Transform rot = Transform::rotate(37.0f, Vec3f(1, 2, 3)) * Transform::translate(Vec3f(3.1f, -7.7f, 1.3f));
  std::vector<Vec3f> p;
  for (int y = 0; y <= kN; ++y)
    for (int x = 0; x <= kN; ++x)
      p.push_back(rot.point(Vec3f(x + 0.3f * (rng.next_float() - 0.5f), y + 0.3f * (rng.next_float() - 0.5f), 0.0f)));
  std::vector<uint32_t> idx;
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const uint32_t a = uint32_t(y * (kN + 1) + x), b = a + 1, c = a + kN + 1, d = c + 1;
      idx.insert(idx.end(), {a, b, d, a, d, c});
    }
  auto any_hit = [&](const Ray& r) {
    const WatertightRay w = make_watertight_ray(r);
    TriangleHit th;
    for (size_t i = 0; i < idx.size(); i += 3)
      if (intersect_triangle(w, p[idx[i]], p[idx[i + 1]], p[idx[i + 2]], 0.0f, kInfinity, th)) return true;
    return false;
  };
  size_t misses = 0, rays = 0;
  for (int i = 0; i < 40000; ++i) {
    // An interior vertex or a point on an interior edge, as exactly as floats allow.
    const int x = 1 + int(rng.next_float() * (kN - 2)), y = 1 + int(rng.next_float() * (kN - 2));
    const uint32_t a = uint32_t(y * (kN + 1) + x);
    const uint32_t nb[] = {a + 1, a + kN + 1, a + kN + 2};
    const float s = (i % 4 == 0) ? 0.0f : rng.next_float();
    const Vec3f target = p[a] + (p[nb[i % 3]] - p[a]) * s;
    Vec3f w = sample_uniform_sphere(rng.next_2d());
    if (std::abs(dot(w, normalize(rot.normal(Vec3f(0, 0, 1))))) < 0.05f) continue;  // not along the plane
    const Vec3f o = target + w * (1.0f + 20.0f * rng.next_float());
    ++rays;
    if (!any_hit(Ray{o, target - o})) ++misses;
  }
  EXPECT_EQ(misses, 0u) << "of " << rays << " rays through shared edges and vertices";
}

}  // namespace
}  // namespace kiln
