#include "core/transform.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/frame.h"
#include "core/rng.h"

namespace kiln {
namespace {

// Transforms are composed in float; a handful of ulps on unit-scale values.
constexpr float kTol = 1e-5f;

void expect_vec_near(Vec3f a, Vec3f b, float tol, const char* what = "") {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

Vec3f random_vec(Rng& rng, float scale = 1.0f) {
  return Vec3f(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f) * (2.0f * scale);
}

// A random well-conditioned affine transform: translate * rotate * non-uniform scale (possibly mirrored).
Transform random_affine(Rng& rng) {
  auto scale_factor = [&] {
    const float s = 0.5f + 1.5f * rng.next_float();
    return rng.next_float() < 0.5f ? -s : s;
  };
  return Transform::translate(random_vec(rng, 5.0f)) *
         Transform::rotate(360.0f * rng.next_float(), random_vec(rng) + Vec3f(0.0f, 0.0f, 1.5f)) *
         Transform::scale(Vec3f(scale_factor(), scale_factor(), scale_factor()));
}

TEST(Transform, IdentityByDefault) {
  const Transform t;
  EXPECT_TRUE(t.is_identity());
  EXPECT_TRUE(t.inverse().is_identity());
  EXPECT_EQ(t.point(Vec3f(1, 2, 3)), Vec3f(1, 2, 3));
  EXPECT_FALSE(Transform::translate(Vec3f(0, 0, 1)).is_identity());
}

TEST(Transform, InverseUndoesRandomAffineTransforms) {
  Rng rng(21, 0);
  for (int k = 0; k < 200; ++k) {
    const Transform t = random_affine(rng);
    const Vec3f p = random_vec(rng, 3.0f);
    expect_vec_near(t.inverse().point(t.point(p)), p, 1e-4f, "point");
    expect_vec_near(t.inverse().vector(t.vector(p)), p, 1e-4f, "vector");
    // The cached inverse agrees with a fresh Gauss-Jordan inverse, and M * M^-1 = I.
    const Transform fresh = Transform::from_matrix(t.matrix());
    const Mat4 prod = t.matrix() * fresh.inverse_matrix();
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        EXPECT_NEAR(fresh.inverse_matrix().m[i][j], t.inverse_matrix().m[i][j], 1e-4f);
        EXPECT_NEAR(prod.m[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
      }
  }
}

TEST(Transform, InverseOfGeneralMatrix) {
  Mat4 m;
  const float v[4][4] = {{2, 1, 0, 3}, {0, 1, 4, -1}, {1, 0, 1, 2}, {0.5f, 0.25f, 0, 1}};  // projective last row
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m.m[i][j] = v[i][j];
  const auto inv = m.inverse();
  ASSERT_TRUE(inv.has_value());
  const Mat4 a = m * *inv, b = *inv * m;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      EXPECT_NEAR(a.m[i][j], i == j ? 1.0f : 0.0f, kTol);
      EXPECT_NEAR(b.m[i][j], i == j ? 1.0f : 0.0f, kTol);
    }
  // Projective points divide by w, and the inverse maps them back.
  const Transform t = Transform::from_matrix(m);
  const Vec3f p(0.3f, -0.7f, 1.1f);
  expect_vec_near(t.inverse().point(t.point(p)), p, kTol);
}

TEST(Transform, CompositionAppliesRightOperandFirst) {
  const Transform t = Transform::translate(Vec3f(1, 0, 0)) * Transform::scale(Vec3f(2, 2, 2));
  EXPECT_EQ(t.point(Vec3f(1, 1, 1)), Vec3f(3, 2, 2));  // scaled, then translated
  const Transform u = Transform::scale(Vec3f(2, 2, 2)) * Transform::translate(Vec3f(1, 0, 0));
  EXPECT_EQ(u.point(Vec3f(1, 1, 1)), Vec3f(4, 2, 2));  // translated, then scaled
  Rng rng(22, 0);
  for (int k = 0; k < 50; ++k) {
    const Transform a = random_affine(rng), b = random_affine(rng);
    const Vec3f p = random_vec(rng);
    expect_vec_near((a * b).point(p), a.point(b.point(p)), 1e-4f);
    expect_vec_near((a * b).inverse().point(p), b.inverse().point(a.inverse().point(p)), 1e-4f);
  }
}

TEST(Transform, RotationFollowsRightHandRule) {
  // 90 degrees about each axis maps the next axis onto the one after (x -> y about z, y -> z about x, z -> x about y).
  expect_vec_near(Transform::rotate(90, Vec3f(0, 0, 1)).vector(Vec3f(1, 0, 0)), Vec3f(0, 1, 0), kTol);
  expect_vec_near(Transform::rotate(90, Vec3f(0, 0, 1)).vector(Vec3f(0, 1, 0)), Vec3f(-1, 0, 0), kTol);
  expect_vec_near(Transform::rotate(90, Vec3f(1, 0, 0)).vector(Vec3f(0, 1, 0)), Vec3f(0, 0, 1), kTol);
  expect_vec_near(Transform::rotate(90, Vec3f(0, 1, 0)).vector(Vec3f(0, 0, 1)), Vec3f(1, 0, 0), kTol);
  // The axis is normalised and negating it reverses the sense.
  expect_vec_near(Transform::rotate(90, Vec3f(0, 0, 7)).vector(Vec3f(1, 0, 0)), Vec3f(0, 1, 0), kTol);
  expect_vec_near(Transform::rotate(90, Vec3f(0, 0, -1)).vector(Vec3f(1, 0, 0)), Vec3f(0, -1, 0), kTol);
  // 120 degrees about (1,1,1) cycles the axes x -> y -> z.
  const Transform r = Transform::rotate(120, Vec3f(1, 1, 1));
  expect_vec_near(r.vector(Vec3f(1, 0, 0)), Vec3f(0, 1, 0), kTol);
  expect_vec_near(r.vector(Vec3f(0, 1, 0)), Vec3f(0, 0, 1), kTol);
  // The axis itself is fixed, rotations keep lengths and points rotate about the origin.
  expect_vec_near(r.vector(Vec3f(2, 2, 2)), Vec3f(2, 2, 2), kTol);
  expect_vec_near(Transform::rotate(180, Vec3f(0, 1, 0)).point(Vec3f(1, 5, 0)), Vec3f(-1, 5, 0), kTol);
  Rng rng(23, 0);
  for (int k = 0; k < 50; ++k) {
    const Transform t = Transform::rotate(720.0f * rng.next_float() - 360.0f, random_vec(rng) + Vec3f(0, 0.01f, 0));
    const Vec3f v = random_vec(rng);
    EXPECT_NEAR(length(t.vector(v)), length(v), kTol);
    EXPECT_FALSE(t.swaps_handedness());
  }
}

TEST(Transform, VectorsIgnoreTranslation) {
  const Transform t = Transform::translate(Vec3f(5, -3, 2));
  EXPECT_EQ(t.vector(Vec3f(1, 2, 3)), Vec3f(1, 2, 3));
  EXPECT_EQ(t.normal(Vec3f(0, 0, 1)), Vec3f(0, 0, 1));
  EXPECT_EQ(t.point(Vec3f(1, 2, 3)), Vec3f(6, -1, 5));
}

TEST(Transform, NormalsUseInverseTranspose) {
  // Under non-uniform scale, transforming a normal like a vector breaks perpendicularity; the inverse transpose
  // keeps it perpendicular to every transformed tangent.
  const Transform s = Transform::scale(Vec3f(4, 1, 1));
  const Vec3f n = normalize(Vec3f(1, 1, 0)), tangent(1, -1, 0);
  EXPECT_GT(std::abs(dot(s.vector(n), s.vector(tangent))), 1.0f);
  EXPECT_NEAR(dot(s.normal(n), s.vector(tangent)), 0.0f, kTol);
  expect_vec_near(s.normal(Vec3f(1, 0, 0)), Vec3f(0.25f, 0, 0), kTol);
  Rng rng(24, 0);
  for (int k = 0; k < 200; ++k) {
    const Transform t = random_affine(rng);
    const Vec3f nn = normalize(random_vec(rng) + Vec3f(0, 0, 0.1f));
    Vec3f t1, t2;
    coordinate_system(nn, t1, t2);
    const Vec3f tn = normalize(t.normal(nn));
    EXPECT_NEAR(dot(tn, normalize(t.vector(t1))), 0.0f, 1e-4f);
    EXPECT_NEAR(dot(tn, normalize(t.vector(t2))), 0.0f, 1e-4f);
  }
}

TEST(Transform, SingularMatricesThrow) {
  Mat4 m = Mat4::identity();
  m.m[1][1] = 0.0f;
  EXPECT_THROW(Transform::from_matrix(m), Error);
  EXPECT_FALSE(m.inverse().has_value());
  Mat4 dependent = Mat4::identity();  // row 2 = row 0 + row 1
  dependent.m[0][1] = 2.0f;
  dependent.m[2][0] = 1.0f;
  dependent.m[2][1] = 3.0f;
  dependent.m[2][2] = 0.0f;
  EXPECT_THROW(Transform::from_matrix(dependent), Error);
  EXPECT_THROW(Transform::from_matrix(Mat4{}), Error);  // all zeros
  EXPECT_THROW(Transform::scale(Vec3f(1, 0, 1)), Error);
  EXPECT_THROW(Transform::rotate(30, Vec3f(0, 0, 0)), Error);
  try {
    Transform::from_matrix(m);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
  }
}

TEST(Transform, SwapsHandedness) {
  EXPECT_FALSE(Transform().swaps_handedness());
  EXPECT_TRUE(Transform::scale(Vec3f(-1, 1, 1)).swaps_handedness());
  EXPECT_FALSE(Transform::scale(Vec3f(-1, -1, 1)).swaps_handedness());
  EXPECT_TRUE(Transform::scale(Vec3f(-2, -3, -0.5f)).swaps_handedness());
  EXPECT_FALSE(Transform::translate(Vec3f(-1, -1, -1)).swaps_handedness());
  EXPECT_TRUE((Transform::rotate(37, Vec3f(1, 2, 3)) * Transform::scale(Vec3f(1, 1, -1))).swaps_handedness());
  Mat4 swap_xy;  // exchanging two axes is a reflection
  swap_xy.m[0][1] = swap_xy.m[1][0] = swap_xy.m[2][2] = swap_xy.m[3][3] = 1.0f;
  EXPECT_TRUE(Transform::from_matrix(swap_xy).swaps_handedness());
  // A mirrored frame flips the cross product of transformed tangents relative to the transformed normal.
  Rng rng(25, 0);
  for (int k = 0; k < 100; ++k) {
    const Transform t = random_affine(rng);
    const Vec3f c = cross(t.vector(Vec3f(1, 0, 0)), t.vector(Vec3f(0, 1, 0)));
    EXPECT_EQ(dot(c, t.normal(Vec3f(0, 0, 1))) < 0.0f, t.swaps_handedness());
  }
}

TEST(Transform, BoundsContainTransformedCorners) {
  const Bounds3f unit(Vec3f(0, 0, 0), Vec3f(1, 1, 1));
  const Bounds3f b = Transform::rotate(45, Vec3f(0, 0, 1)).bounds(unit);
  const float h = std::sqrt(0.5f);
  expect_vec_near(b.lo, Vec3f(-h, 0, 0), kTol);
  expect_vec_near(b.hi, Vec3f(h, 2 * h, 1), kTol);
  EXPECT_TRUE(Transform::translate(Vec3f(1, 2, 3)).bounds(Bounds3f()).empty());
  Rng rng(26, 0);
  for (int k = 0; k < 50; ++k) {
    const Transform t = random_affine(rng);
    const Bounds3f tb = t.bounds(unit);
    for (int i = 0; i < 20; ++i) {
      const Vec3f p = t.point(Vec3f(rng.next_float(), rng.next_float(), rng.next_float()));
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(p[a], tb.lo[a] - 1e-4f);
        EXPECT_LE(p[a], tb.hi[a] + 1e-4f);
      }
    }
  }
}

}  // namespace
}  // namespace kiln
