#include "renderer/accel/exact_hit.h"

#include <gtest/gtest.h>

#include "accel_test_util.h"

namespace kiln {
namespace {

TEST(ExactHit, TrianglesSpheresAndInstances) {
  WorldGeometry g;
  TriangleMesh tri;
  tri.p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.idx = {0, 1, 2};
  test::add_mesh(g, tri);
  test::add_sphere(g, Vec3f(0, 0, 0), 1.0f, Transform::translate(Vec3f(5, 0, 0)) * Transform::scale(Vec3f(2, 1, 1)));
  test::add_instance(g, test::add_prototype(g, tri), Transform::translate(Vec3f(0, 0, 10)));

  ExactHit h = exact_hit(g, Ray{Vec3f(0.25f, 0.25f, 2), Vec3f(0, 0, -1)}, 0, 0);
  EXPECT_TRUE(h.hit);
  EXPECT_DOUBLE_EQ(h.t, 2.0);
  EXPECT_FALSE(h.near_edge);
  // Behind the origin: the line crosses it, the ray does not.
  h = exact_hit(g, Ray{Vec3f(0.25f, 0.25f, 2), Vec3f(0, 0, 1)}, 0, 0);
  EXPECT_FALSE(h.hit);
  EXPECT_DOUBLE_EQ(h.t, -2.0);
  // A hair beside the hypotenuse: a miss, but within float noise of the edge.
  h = exact_hit(g, Ray{Vec3f(0.500001f, 0.5f, 2), Vec3f(0, 0, -1)}, 0, 0);
  EXPECT_FALSE(h.hit);
  EXPECT_TRUE(h.near_edge);
  // Beyond tmax.
  EXPECT_FALSE(exact_hit(g, Ray{Vec3f(0.25f, 0.25f, 2), Vec3f(0, 0, -1), 0.0f, 1.5f}, 0, 0).hit);

  // The ellipsoid spans x in [3, 7].
  h = exact_hit(g, Ray{Vec3f(0, 0, 0), Vec3f(1, 0, 0)}, 1, 0);
  EXPECT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 3.0, 1e-12);
  h = exact_hit(g, Ray{Vec3f(5, 0, 0), Vec3f(1, 0, 0)}, 1, 0);  // from inside: the far side
  EXPECT_NEAR(h.t, 2.0, 1e-12);
  EXPECT_FALSE(exact_hit(g, Ray{Vec3f(0, 1.01f, 0), Vec3f(1, 0, 0)}, 1, 0).hit);

  h = exact_hit(g, Ray{Vec3f(0.25f, 0.25f, 12), Vec3f(0, 0, -1)}, 2, 0);
  EXPECT_TRUE(h.hit);
  EXPECT_DOUBLE_EQ(h.t, 2.0);
}

}  // namespace
}  // namespace kiln
