// The bounds of the light hierarchy (lights/light_bounds.h): merged bounds hold both inputs (box and cone of
// normals), the 4-wide importance is the scalar one lane by lane, and the importance of a point light is its
// irradiance formula.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "lights/light_bounds.h"

namespace kiln {
namespace {

Vec3f random_direction(Rng& rng) {
  const float z = 1.0f - 2.0f * rng.next_float(), phi = 2.0f * kPi * rng.next_float();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Accurate near 0 and pi, where acos of the dot product loses half the digits.
float angle_between(Vec3f a, Vec3f b) {
  const double d = double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
  const double s = std::hypot(std::hypot(double(a.x) - b.x, double(a.y) - b.y), double(a.z) - b.z);
  return float(d < 0.0 ? M_PI - 2.0 * std::asin(std::min(1.0, std::hypot(std::hypot(double(a.x) + b.x, double(a.y) + b.y),
                                                                            double(a.z) + b.z) / 2.0))
                       : 2.0 * std::asin(std::min(1.0, s / 2.0)));
}

Vec3f random_point(Rng& rng, float extent) {
  return {extent * (rng.next_float() - 0.5f), extent * (rng.next_float() - 0.5f), extent * (rng.next_float() - 0.5f)};
}

// Bounds of a random triangle, point, spot or two-sided emitter, or a merge of a few of them.
LightBounds random_bounds(Rng& rng, int merges) {
  LightBounds b;
  for (int i = 0; i <= merges; ++i) {
    LightBounds e;
    const Vec3f c = random_point(rng, 10.0f);
    e.box = Bounds3f(c, c + random_point(rng, 2.0f));
    e.axis = random_direction(rng);
    e.phi = 0.1f + 10.0f * rng.next_float();
    switch (rng.next_u32() % 4) {
      case 0: e.cos_theta_o = 1.0f; e.cos_theta_e = 0.0f; break;                         // one-sided flat
      case 1: e.cos_theta_o = 1.0f; e.cos_theta_e = 0.0f; e.two_sided = true; break;     // two-sided flat
      case 2: e.box = Bounds3f(c); e.cos_theta_o = -1.0f; e.cos_theta_e = 0.0f; break;  // point
      default: e.box = Bounds3f(c); e.cos_theta_o = 0.9f; e.cos_theta_e = std::cos(2.0f); break;  // wide spot
    }
    b = merge(b, e);
  }
  return b;
}

TEST(LightBounds, MergeHoldsBothBoxesAndConesOfNormals) {
  Rng rng(1, 2);
  for (int k = 0; k < 20000; ++k) {
    const LightBounds a = random_bounds(rng, int(rng.next_u32() % 3)), b = random_bounds(rng, int(rng.next_u32() % 3));
    const LightBounds m = merge(a, b);
    for (const LightBounds* x : {&a, &b}) {
      EXPECT_LE(m.box.lo.x, x->box.lo.x);
      EXPECT_GE(m.box.hi.z, x->box.hi.z);
      EXPECT_LE(m.cos_theta_e, x->cos_theta_e);
      // The input cone lies inside the merged one: the angle to its axis plus its half-angle.
      const float inner = angle_between(m.axis, x->axis) + std::acos(x->cos_theta_o);
      if (m.cos_theta_o > -1.0f) {
        EXPECT_LE(inner, std::acos(m.cos_theta_o) + 1e-4f) << k;
      }
    }
    EXPECT_FLOAT_EQ(m.phi, a.phi + b.phi);
    EXPECT_NEAR(length(m.axis), 1.0f, 1e-5f);
  }
}

TEST(LightBounds, FourWideImportanceIsTheScalarOneLaneByLane) {
  Rng rng(3, 4);
  int zero = 0, inside = 0, positive = 0;
  for (int k = 0; k < 20000; ++k) {
    ImportanceBounds4 four;
    ImportanceBounds one[4];
    const int lanes = 1 + int(rng.next_u32() % 4);
    for (int l = 0; l < lanes; ++l) {
      one[l] = importance_bounds(random_bounds(rng, int(rng.next_u32() % 4)));
      four.set(l, one[l]);
    }
    const Vec3f p = random_point(rng, 24.0f);
    const Vec3f n = k % 5 == 0 ? Vec3f(0.0f) : random_direction(rng);
    float got[4];
    importance4(four, p, n, got);
    for (int l = 0; l < 4; ++l) {
      if (l >= lanes) {
        EXPECT_EQ(got[l], 0.0f);
        continue;
      }
      const float want = importance(one[l], p, n);
      EXPECT_EQ(got[l], want) << "case " << k << " lane " << l;
      zero += want == 0.0f;
      inside += length_squared(p - one[l].center) <= one[l].radius_sq;
      positive += want > 0.0f;
    }
  }
  // Every branch was taken.
  EXPECT_GT(zero, 1000);
  EXPECT_GT(inside, 1000);
  EXPECT_GT(positive, 10000);
}

// An isotropic point of intensity I seen at distance d from a surface whose normal makes angle t with it:
// irradiance I cos(t) / d^2, which the importance is exactly (nothing to bound).
TEST(LightBounds, ImportanceOfAPointLightIsItsIrradiance) {
  std::vector<EmitterBounds> e;
  ASSERT_TRUE(append_emitter_bounds(PointLight({1, 2, 3}, Rgb(2.0f)), 0, e));
  const ImportanceBounds b = importance_bounds(e.at(0).bounds);
  const Vec3f p{4, 6, 3};  // d = 5
  const Vec3f n = normalize(Vec3f{1, 1, 0});
  EXPECT_NEAR(importance(b, p, n), 2.0f * std::abs(dot(normalize(Vec3f{3, 4, 0}), n)) / 25.0f, 1e-6f);
  EXPECT_NEAR(importance(b, p, Vec3f(0.0f)), 2.0f / 25.0f, 1e-6f);
}

// Lights at infinity are not bounded; every other kind is, mesh lights triangle by triangle.
TEST(LightBounds, EveryLightWithAPositionIsBounded) {
  std::vector<EmitterBounds> e;
  EXPECT_FALSE(append_emitter_bounds(DirectionalLight({0, 0, -1}, Rgb(1.0f), 10.0f), 0, e));
  EXPECT_FALSE(append_emitter_bounds(InfiniteLight(Rgb(1.0f), 10.0f), 0, e));
  EXPECT_TRUE(e.empty());
  const std::vector<Vec3f> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<uint32_t> idx{0, 1, 2, 1, 3, 2, 0, 0, 1};  // the last triangle is degenerate
  EXPECT_TRUE(append_emitter_bounds(MeshLight(p, idx, Rgb(3.0f)), 7, e));
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[1].light, 7u);
  EXPECT_EQ(e[1].part, 1u);
  EXPECT_FLOAT_EQ(e[0].bounds.phi, 3.0f * 0.5f);  // L * area
  EXPECT_EQ(e[2].bounds.phi, 0.0f);
  EXPECT_TRUE(append_emitter_bounds(SpotLight({0, 0, 0}, {0, 0, -1}, Rgb(1.0f), 90.0f, 30.0f), 1, e));
  EXPECT_TRUE(append_emitter_bounds(AreaLight::square({0, 0, 0}, {0, 0, 1}, 1.0f, Rgb(1.0f)), 2, e));
  EXPECT_TRUE(append_emitter_bounds(SphereLight({0, 0, 0}, 1.0f, Transform::scale({2, 1, 1}), Rgb(1.0f)), 3, e));
  const LightBounds& sphere = e.back().bounds;
  EXPECT_NEAR(sphere.box.lo.x, -2.0f, 1e-5f);
  EXPECT_NEAR(sphere.box.hi.y, 1.0f, 1e-5f);
  EXPECT_EQ(e.back().part, kWholeLight);
}

}  // namespace
}  // namespace kiln
