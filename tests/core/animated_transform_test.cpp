// pbrt-v4's interpolated transforms (core/animated_transform.h) against their closed forms: the keyframes at and
// beyond the transform times, a translation that moves linearly, a rotation that turns at constant angular speed
// along the shorter arc (a point keeps its distance from the axis, which a blend of matrices would not), a stretch
// that grows linearly while the rotation turns, mirrored keyframes, and motion bounds that hold every sampled
// position of the moving box.
#include "core/animated_transform.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/rng.h"

namespace kiln {
namespace {

constexpr float kTol = 2e-5f;

void expect_matrix_near(const Transform& a, const Transform& b, float tol, const char* what) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(a.matrix().m[size_t(r)][size_t(c)], b.matrix().m[size_t(r)][size_t(c)], tol) << what;
      EXPECT_NEAR(a.inverse_matrix().m[size_t(r)][size_t(c)], b.inverse_matrix().m[size_t(r)][size_t(c)], tol)
          << what << " (inverse)";
    }
}

TEST(AnimatedTransform, KeyframesHoldAtAndBeyondTheirTimes) {
  const Transform a = Transform::translate({1, 2, 3}) * Transform::rotate(30, {0, 1, 0});
  const Transform b = Transform::translate({-4, 0, 1}) * Transform::rotate(100, {1, 1, 0}) * Transform::scale({2, 2, 2});
  const AnimatedTransform at(a, 0.25f, b, 0.75f);
  ASSERT_TRUE(at.animated());
  EXPECT_EQ(at.at(0.25f).matrix(), a.matrix());
  EXPECT_EQ(at.at(-3.0f).matrix(), a.matrix());
  EXPECT_EQ(at.at(0.75f).matrix(), b.matrix());
  EXPECT_EQ(at.at(9.0f).matrix(), b.matrix());
  // Just inside the interval the decomposition rebuilds each keyframe.
  expect_matrix_near(at.at(0.25f + 1e-6f), a, 1e-4f, "near the start");
  expect_matrix_near(at.at(0.75f - 1e-6f), b, 1e-4f, "near the end");
  EXPECT_FALSE(AnimatedTransform(a, 0.0f, a, 1.0f).animated());
}

// killeroo-moving's case: the keyframes differ by a translation only, so every point moves on a straight line at
// constant speed.
TEST(AnimatedTransform, TranslationMovesLinearly) {
  const Transform base = Transform::scale({0.5f, 0.5f, 0.5f}) * Transform::rotate(-60, {0, 0, 1});
  const Transform start = base * Transform::translate({35, 35, 35}), end = base;
  const AnimatedTransform at(start, 0.0f, end, 1.0f);
  const Vec3f p(3, -2, 7);
  for (float t : {0.1f, 0.5f, 0.9f}) {
    const Vec3f expected = lerp(t, start.point(p), end.point(p));
    const Vec3f got = at.at(t).point(p);
    EXPECT_NEAR(length(got - expected), 0.0f, kTol * 40) << "t " << t;
  }
  EXPECT_EQ(at.rotation_angle(), 0.0f);
}

// Slerp: a quarter turn about z reaches 45 degrees half way, and a point at radius 2 stays at radius 2 all the way
// (a linear blend of the two matrices would pass through radius 2 cos 45 = 1.41).
TEST(AnimatedTransform, RotationTurnsAtConstantSpeedOnTheShorterArc) {
  const AnimatedTransform quarter(Transform(), 0.0f, Transform::rotate(90, {0, 0, 1}), 1.0f);
  EXPECT_NEAR(quarter.rotation_angle(), kPi / 2, 1e-6f);
  for (float t : {0.2f, 0.5f, 0.7f}) {
    const Vec3f p = quarter.at(t).point({2, 0, 0});
    EXPECT_NEAR(length(p), 2.0f, kTol) << "t " << t;
    EXPECT_NEAR(std::atan2(p.y, p.x), t * kPi / 2, kTol) << "t " << t;
  }
  // 270 degrees one way is 90 degrees the other: the shorter arc turns by -90.
  const AnimatedTransform back(Transform(), 0.0f, Transform::rotate(270, {0, 0, 1}), 1.0f);
  const Vec3f p = back.at(0.5f).point({1, 0, 0});
  EXPECT_NEAR(std::atan2(p.y, p.x), -kPi / 4, kTol);
}

// M = R(angle) S(diag): the stretch grows linearly while the rotation turns, and mirrored keyframes interpolate as
// a mirrored stretch under a proper rotation.
TEST(AnimatedTransform, StretchInterpolatesLinearlyUnderTheRotation) {
  const Transform a = Transform::rotate(10, {0, 0, 1}) * Transform::scale({1, 2, 1});
  const Transform b = Transform::rotate(70, {0, 0, 1}) * Transform::scale({3, 4, 1});
  const AnimatedTransform at(a, 0.0f, b, 1.0f);
  expect_matrix_near(at.at(0.5f), Transform::rotate(40, {0, 0, 1}) * Transform::scale({2, 3, 1}), kTol, "middle");
  const Transform m = Transform::scale({-1, 1, 1});
  const AnimatedTransform mirrored(a * m, 0.0f, b * m, 1.0f);
  expect_matrix_near(mirrored.at(0.5f), Transform::rotate(40, {0, 0, 1}) * Transform::scale({-2, 3, 1}), kTol,
                     "mirrored");
  EXPECT_THROW(AnimatedTransform(a, 0.0f, b * m, 1.0f), Error);
}

// Every sampled position of every sampled point of the box lies in the motion bounds, for random keyframes with
// large rotations; the bounds are not much larger than the sampled extent.
TEST(AnimatedTransform, MotionBoundsHoldTheWholePath) {
  Rng rng(11, 0);
  auto rnd = [&](float s) { return (rng.next_float() - 0.5f) * 2.0f * s; };
  for (int trial = 0; trial < 20; ++trial) {
    auto key = [&] {
      return Transform::translate({rnd(5), rnd(5), rnd(5)}) *
             Transform::rotate(rnd(180), Vec3f(rnd(1), rnd(1), rnd(1)) + Vec3f(0, 0, 1.5f)) *
             Transform::scale({1 + rng.next_float(), 1 + rng.next_float(), 1 + rng.next_float()});
    };
    const AnimatedTransform at(key(), 0.0f, key(), 1.0f);
    const Bounds3f box({-1, -0.5f, -2}, {1, 0.5f, 2});
    const float ta = rng.next_float() * 0.5f, tb = 0.5f + rng.next_float() * 0.5f;
    const Bounds3f bounds = at.motion_bounds(box, ta, tb);
    Bounds3f seen;
    for (int i = 0; i <= 400; ++i) {
      const Transform x = at.at(ta + (tb - ta) * float(i) / 400.0f);
      for (int c = 0; c < 8; ++c) {
        const Vec3f p((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y, (c & 4) ? box.hi.z : box.lo.z);
        const Vec3f q = x.point(p);
        seen.extend(q);
        for (int k = 0; k < 3; ++k) {
          ASSERT_GE(q[k], bounds.lo[k]) << "trial " << trial << " step " << i;
          ASSERT_LE(q[k], bounds.hi[k]) << "trial " << trial << " step " << i;
        }
      }
    }
    for (int k = 0; k < 3; ++k)
      EXPECT_LT(bounds.hi[k] - bounds.lo[k], 1.2f * (seen.hi[k] - seen.lo[k]) + 0.1f) << "trial " << trial;
  }
}

}  // namespace
}  // namespace kiln
