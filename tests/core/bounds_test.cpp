#include "core/bounds.h"

#include <gtest/gtest.h>

namespace kiln {
namespace {

TEST(Bounds3f, DefaultIsEmpty) {
  const Bounds3f b;
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(b.surface_area(), 0.0f);
  EXPECT_EQ(b.extent(), 0.0f);
}

TEST(Bounds3f, CornersInAnyOrder) {
  const Bounds3f b(Vec3f(1, -2, 3), Vec3f(-1, 2, 0));
  EXPECT_EQ(b.lo, Vec3f(-1, -2, 0));
  EXPECT_EQ(b.hi, Vec3f(1, 2, 3));
  EXPECT_EQ(b.diagonal(), Vec3f(2, 4, 3));
  EXPECT_EQ(b.center(), Vec3f(0, 0, 1.5f));
  EXPECT_FLOAT_EQ(b.surface_area(), 2.0f * (8 + 12 + 6));
  EXPECT_FLOAT_EQ(b.extent(), std::sqrt(29.0f));
}

TEST(Bounds3f, PointBoundsAreDegenerateButNotEmpty) {
  const Bounds3f b(Vec3f(1, 2, 3));
  EXPECT_FALSE(b.empty());
  EXPECT_EQ(b.surface_area(), 0.0f);
  EXPECT_EQ(b.center(), Vec3f(1, 2, 3));
  // A flat box (one zero extent) still has the area of its two faces.
  const Bounds3f flat(Vec3f(0, 0, 0), Vec3f(2, 3, 0));
  EXPECT_FALSE(flat.empty());
  EXPECT_FLOAT_EQ(flat.surface_area(), 12.0f);
}

TEST(Bounds3f, ExtendAndMerge) {
  Bounds3f b;
  b.extend(Vec3f(1, 1, 1));
  EXPECT_FALSE(b.empty());
  EXPECT_EQ(b.lo, Vec3f(1, 1, 1));
  b.extend(Vec3f(-1, 2, 0));
  EXPECT_EQ(b.lo, Vec3f(-1, 1, 0));
  EXPECT_EQ(b.hi, Vec3f(1, 2, 1));
  // Merging with an empty box changes nothing, in either order.
  const Bounds3f e;
  const Bounds3f m1 = merge(b, e), m2 = merge(e, b);
  EXPECT_EQ(m1.lo, b.lo);
  EXPECT_EQ(m1.hi, b.hi);
  EXPECT_EQ(m2.lo, b.lo);
  EXPECT_EQ(m2.hi, b.hi);
  EXPECT_TRUE(merge(e, e).empty());
  const Bounds3f c(Vec3f(5, 5, 5), Vec3f(6, 6, 6));
  const Bounds3f u = merge(b, c);
  EXPECT_EQ(u.lo, Vec3f(-1, 1, 0));
  EXPECT_EQ(u.hi, Vec3f(6, 6, 6));
}

}  // namespace
}  // namespace kiln
