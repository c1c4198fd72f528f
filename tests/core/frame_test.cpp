#include "core/frame.h"

#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/sampling.h"

namespace kiln {
namespace {

// Orthonormality of a float basis: a few ulps.
constexpr float kTol = 2e-6f;

void expect_orthonormal_right_handed(Vec3f n) {
  const Frame f(n);
  SCOPED_TRACE(testing::Message() << "n = (" << n.x << ", " << n.y << ", " << n.z << ")");
  EXPECT_NEAR(length(f.s), 1.0f, kTol);
  EXPECT_NEAR(length(f.t), 1.0f, kTol);
  EXPECT_EQ(f.n, n);
  EXPECT_NEAR(dot(f.s, f.t), 0.0f, kTol);
  EXPECT_NEAR(dot(f.s, n), 0.0f, kTol);
  EXPECT_NEAR(dot(f.t, n), 0.0f, kTol);
  // s x t = n, so local z is the normal and the frame is right-handed.
  const Vec3f c = cross(f.s, f.t);
  EXPECT_NEAR(c.x, n.x, kTol);
  EXPECT_NEAR(c.y, n.y, kTol);
  EXPECT_NEAR(c.z, n.z, kTol);
  EXPECT_TRUE(is_finite(f.s) && is_finite(f.t));
}

TEST(Frame, OrthonormalForPolesAndAxes) {
  for (Vec3f n : {Vec3f(0, 0, 1), Vec3f(0, 0, -1), Vec3f(1, 0, 0), Vec3f(-1, 0, 0), Vec3f(0, 1, 0),
                  Vec3f(0, -1, 0)})
    expect_orthonormal_right_handed(n);
  // Normals a hair away from the poles, where a naive construction divides by ~0.
  for (float e : {1e-3f, 1e-5f, 1e-7f})
    for (float z : {1.0f, -1.0f}) expect_orthonormal_right_handed(normalize(Vec3f(e, -e, z)));
  // A negative-zero z picks the -z branch and must still be valid.
  expect_orthonormal_right_handed(Vec3f(1.0f, 0.0f, -0.0f));
}

TEST(Frame, OrthonormalForRandomNormals) {
  Rng rng(41, 0);
  for (int k = 0; k < 20000; ++k) expect_orthonormal_right_handed(sample_uniform_sphere(rng.next_2d()));
}

TEST(Frame, LocalWorldRoundTrip) {
  Rng rng(42, 0);
  for (int k = 0; k < 1000; ++k) {
    const Frame f(sample_uniform_sphere(rng.next_2d()));
    const Vec3f v = sample_uniform_sphere(rng.next_2d());
    const Vec3f local = f.to_local(v);
    const Vec3f back = f.to_world(local);
    EXPECT_NEAR(back.x, v.x, 1e-5f);
    EXPECT_NEAR(back.y, v.y, 1e-5f);
    EXPECT_NEAR(back.z, v.z, 1e-5f);
    EXPECT_NEAR(cos_theta(local), dot(v, f.n), 1e-6f);
    EXPECT_NEAR(sin2_theta(local), 1.0f - sqr(dot(v, f.n)), 1e-5f);
  }
  const Frame id;
  EXPECT_EQ(id.to_local(Vec3f(1, 2, 3)), Vec3f(1, 2, 3));
}

TEST(Frame, LocalTrigonometry) {
  EXPECT_EQ(cos_theta(Vec3f(0, 0, 1)), 1.0f);
  EXPECT_EQ(abs_cos_theta(Vec3f(0, 0.6f, -0.8f)), 0.8f);
  EXPECT_EQ(sin2_theta(Vec3f(0, 0, 1.0000001f)), 0.0f);  // clamped, never negative
  EXPECT_TRUE(same_hemisphere(Vec3f(0, 0, 1), Vec3f(1, 0, 0.1f)));
  EXPECT_FALSE(same_hemisphere(Vec3f(0, 0, 1), Vec3f(1, 0, -0.1f)));
  EXPECT_FALSE(same_hemisphere(Vec3f(0, 0, 1), Vec3f(1, 0, 0)));  // grazing counts as neither
}

}  // namespace
}  // namespace kiln
