// pbrt-v4's procedural cloud (media/cloud_medium.h): its density stays in [0, 1], is solid where the height term
// saturates (y <= 0 of the medium's space), vanishes at the top (y = 1) and outside its box, and the noise really
// shapes it (neither empty nor solid in between).
#include <gtest/gtest.h>

#include "core/rng.h"
#include "media/medium.h"

namespace kiln::test {
namespace {

CloudMedium cloud(float density, float wispiness, float frequency, const Bounds3f& box) {
  return CloudMedium(Transform(), box, Rgb(0.1f), Rgb(1.0f), 0.0f, CloudShape{density, wispiness, frequency});
}

Vec3f uniform_in(const Bounds3f& b, Rng& rng) {
  const Vec3f d = b.diagonal();
  return b.lo + Vec3f(d.x * rng.next_float(), d.y * rng.next_float(), d.z * rng.next_float());
}

TEST(CloudMedium, DensityIsInTheUnitIntervalAndSolidWhereTheHeightTermSaturates) {
  const Bounds3f box({-1, -1, -1}, {1, 1.5f, 1});
  Rng rng(11, 2);
  for (const CloudShape shape : {CloudShape{}, CloudShape{8.0f, 3.0f, 2.0f}, CloudShape{0.3f, 0.0f, 11.0f}}) {
    const CloudMedium m = cloud(shape.density, shape.wispiness, shape.frequency, box);
    int below = 0, thin = 0, dense = 0, between = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3f p = uniform_in(box, rng);
      const float d = m.density(p);
      ASSERT_TRUE(d >= 0.0f && d <= 1.0f) << d << " at " << p.x << " " << p.y << " " << p.z;
      if (p.y <= 0.0f) {  // the height term 2 (1/2 - y) adds at least 1
        ++below;
        ASSERT_EQ(d, 1.0f) << "at y = " << p.y;
      } else if (p.y < 0.5f) {  // the height term alone, 1 - 2y, is a lower bound
        ASSERT_GE(d, std::min(1.0f, 1.0f - 2.0f * p.y)) << "at y = " << p.y;
      } else if (p.y < 1.0f) {  // the noise alone: some of the cloud is empty, some solid, some in between
        thin += d == 0.0f;
        dense += d == 1.0f;
        between += d > 0.0f && d < 1.0f;
      }
    }
    EXPECT_GT(below, 5000);
    EXPECT_GT(thin, 100) << "density " << shape.density;
    EXPECT_GT(between, 100) << "density " << shape.density;
    if (shape.density > 1.0f) {
      EXPECT_GT(dense, 100) << "density " << shape.density;
    }
    // At the top of the profile (y = 1) the noise's gain is 0 and so is the density.
    for (int i = 0; i < 200; ++i) EXPECT_EQ(m.density({2 * rng.next_float() - 1, 1.0f, 2 * rng.next_float() - 1}), 0.0f);
  }
}

TEST(CloudMedium, NothingOutsideItsBox) {
  // The box lies where the cloud is solid (y < 0), so only the box can make it empty.
  const Bounds3f box({0.2f, -2.0f, -0.5f}, {0.7f, -0.5f, 0.4f});
  const CloudMedium m = cloud(2.0f, 1.0f, 5.0f, box);
  const Bounds3f around({-1, -3, -2}, {2, 0, 2});
  Rng rng(5, 9);
  int inside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3f p = uniform_in(around, rng);
    const bool in = p.x >= box.lo.x && p.x <= box.hi.x && p.y >= box.lo.y && p.y <= box.hi.y && p.z >= box.lo.z &&
                    p.z <= box.hi.z;
    inside += in;
    ASSERT_EQ(m.density(p), in ? 1.0f : 0.0f) << p.x << " " << p.y << " " << p.z;
  }
  EXPECT_GT(inside, 100);
  // World points reach the medium's space through its transform: at() scales the coefficients by the density.
  const Transform to_world = Transform::translate({3, 0, 0}) * Transform::rotate(90.0f, {0, 0, 1});
  const CloudMedium moved(to_world, box, Rgb(0.1f), Rgb(1.0f, 2.0f, 3.0f), 0.0f, CloudShape{});
  const Vec3f centre = box.center();
  EXPECT_EQ(moved.at(to_world.point(centre)).sigma_s, Rgb(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(moved.at(centre).sigma_s, Rgb(0.0f));
}

}  // namespace
}  // namespace kiln::test
