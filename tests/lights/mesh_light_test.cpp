// MeshLight: irradiance against Lambert's polygon formula, area-proportional triangle choice (chi-square),
// front-side-only emission, pdf consistency and input validation.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "core/error.h"
#include "light_test_util.h"
#include "lights/mesh_light.h"
#include "support/chi2.h"

namespace kiln {
namespace {

using test::estimate;
using test::irradiance_sample;
using test::within_error;

constexpr float kL = 1.7f;
const Rgb kRadiance{kL};
constexpr int kIrradianceSamples = 200000;

MeshLight make(const std::vector<Vec3f>& p, const std::vector<uint32_t>& idx) { return MeshLight(p, idx, kRadiance); }

test::Estimate irradiance(const MeshLight& light, const LightQuery& q, uint64_t seed) {
  return estimate([&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_li(qq, u); }, q, rng); },
                  kIrradianceSamples, seed);
}

TEST(MeshLight, PolygonFormulaMatchesTextbookFormFactor) {
  // Unit-height point below the corner of a 2 x 3 rectangle.
  const std::vector<Vec3f> rect{{0, 0, 1}, {2, 0, 1}, {2, 3, 1}, {0, 3, 1}};
  EXPECT_NEAR(test::polygon_irradiance(rect, {0, 0, 0}, {0, 0, 1}, 1.0),
              test::kPiD * test::corner_rectangle_form_factor(2, 3, 1), 1e-12);
}

TEST(MeshLight, TriangleIrradianceMatchesLambertFormula) {
  // Triangle wound so its normal faces down towards receivers below it.
  const std::vector<Vec3f> tri{{-0.5f, -0.4f, 1.0f}, {0.2f, 0.9f, 1.3f}, {0.8f, -0.3f, 0.9f}};
  const MeshLight light = make(tri, {0, 1, 2});
  ASSERT_LT(cross(tri[1] - tri[0], tri[2] - tri[0]).z, 0.0f);
  for (const LightQuery q : {LightQuery{{0, 0, 0}, {0, 0, 1}}, LightQuery{{0.3f, -0.2f, -0.5f}, normalize(Vec3f{0.3f, 0.2f, 1})},
                             LightQuery{{-2, 1, 0.2f}, normalize(Vec3f{0.5f, -0.2f, 0.4f})}}) {
    const double expected = test::polygon_irradiance(tri, q.p, q.n, kL);
    const auto e = irradiance(light, q, 5);
    EXPECT_EQ(e.invalid, 0);
    EXPECT_TRUE(within_error(e, expected)) << e.mean << " +- " << e.std_error << " vs " << expected;
  }
}

TEST(MeshLight, QuadOfTwoTrianglesMatchesLambertFormula) {
  const std::vector<Vec3f> quad{{-1, -1, 2}, {-1, 1, 2}, {1.5f, 1, 2}, {1.5f, -1, 2}};  // normal -z
  const MeshLight light = make(quad, {0, 1, 2, 0, 2, 3});
  const LightQuery q{{0.2f, 0.1f, 0}, normalize(Vec3f{0.1f, 0.2f, 1})};
  const double expected = test::polygon_irradiance(quad, q.p, q.n, kL);
  const auto e = irradiance(light, q, 6);
  EXPECT_TRUE(within_error(e, expected)) << e.mean << " +- " << e.std_error << " vs " << expected;
  EXPECT_NEAR(light.total_area(), 5.0f, 1e-5f);
}

// Two triangles that make one parallelogram are sampled as it: the sample point is an affine function of u (the
// square's centre goes to the quad's centre, equal steps in u to equal steps on the quad), so the sampler's
// stratification carries over to the lamp; the density stays 1/area, as pdf_li reports for either triangle.
TEST(MeshLight, AQuadLampIsSampledAsOneParallelogram) {
  const std::vector<Vec3f> quad{{-1, -1, 2}, {-0.5f, 1, 2}, {1.5f, 1.2f, 2}, {1.0f, -0.8f, 2}};  // normal -z
  const MeshLight light = make(quad, {0, 1, 2, 0, 2, 3});
  const LightQuery q{{0.2f, 0.1f, 0}, {0, 0, 1}};
  const auto at = [&](Vec2f u) {
    const auto s = light.sample_li(q, u);
    EXPECT_TRUE(s.has_value());
    return s ? s->p_light : Vec3f(0.0f);
  };
  const Vec3f centre = (quad[0] + quad[1] + quad[2] + quad[3]) * 0.25f;
  EXPECT_LT(length(at({0.5f, 0.5f}) - centre), 1e-5f);
  Rng rng(3, 9);
  for (int i = 0; i < 200; ++i) {
    const Vec2f u{0.3f * rng.next_float(), 0.3f * rng.next_float()}, step{0.25f + 0.2f * rng.next_float(), 0.3f};
    const Vec3f d1 = at(u + step) - at(u), d2 = at(Vec2f{u.x + 0.2f, u.y + 0.1f} + step) - at({u.x + 0.2f, u.y + 0.1f});
    EXPECT_LT(length(d1 - d2), 1e-5f) << "sample points are not affine in u";
  }
  for (int i = 0; i < 200; ++i) {
    const auto s = light.sample_li(q, rng.next_2d());
    ASSERT_TRUE(s.has_value());
    const float on0 = light.pdf_li(q, s->p_light, s->n_light, 0), on1 = light.pdf_li(q, s->p_light, s->n_light, 1);
    EXPECT_NEAR(on0, s->pdf, 1e-5f * s->pdf);
    EXPECT_NEAR(on1, s->pdf, 1e-5f * s->pdf);
  }
}

// Pairs that are not one parallelogram facing one way keep the triangle-by-triangle sampling: a trapezoid, and a
// quad whose second triangle is wound the other way (it emits downwards, the first upwards). Their irradiance
// follows Lambert's formula for what really emits towards the receiver.
TEST(MeshLight, TrapezoidsAndMixedWindingsAreSampledTriangleByTriangle) {
  const std::vector<Vec3f> trapezoid{{-1, -1, 2}, {-0.5f, 1, 2}, {0.5f, 1, 2}, {1.0f, -1, 2}};  // normal -z
  const LightQuery below{{0.2f, 0.1f, 0}, normalize(Vec3f{0.1f, 0.2f, 1})};
  const auto e = irradiance(make(trapezoid, {0, 1, 2, 0, 2, 3}), below, 21);
  const double expected = test::polygon_irradiance(trapezoid, below.p, below.n, kL);
  EXPECT_TRUE(within_error(e, expected)) << "trapezoid: " << e.mean << " +- " << e.std_error << " vs " << expected;

  const std::vector<Vec3f> square{{-1, -1, 2}, {-1, 1, 2}, {1, 1, 2}, {1, -1, 2}};
  const MeshLight mixed = make(square, {0, 1, 2, 0, 3, 2});  // first triangle faces -z, second +z
  const auto m = irradiance(mixed, below, 22);
  const double first_only = test::polygon_irradiance({square[0], square[1], square[2]}, below.p, below.n, kL);
  EXPECT_TRUE(within_error(m, first_only)) << "mixed windings: " << m.mean << " +- " << m.std_error << " vs "
                                           << first_only;
}

TEST(MeshLight, EmitsFromTheFrontSideOnly) {
  const std::vector<Vec3f> tri{{0, 0, 1}, {0, 1, 1}, {1, 0, 1}};  // normal -z
  const MeshLight light = make(tri, {0, 1, 2});
  const LightQuery above{{0.2f, 0.2f, 2}, {0, 0, -1}};
  Rng rng(2, 2);
  for (int i = 0; i < 1000; ++i) EXPECT_FALSE(light.sample_li(above, rng.next_2d()).has_value());
  EXPECT_EQ(light.pdf_li(above, {0.2f, 0.2f, 1}, {0, 0, -1}, 0), 0.0f);
  EXPECT_TRUE(light.emitted({0, 0, -1}, {0, 0, 1}).is_black());
  EXPECT_EQ(light.emitted({0, 0, -1}, {0, 0.6f, -0.8f}), kRadiance);
  const LightQuery below{{0.2f, 0.2f, 0}, {0, 0, 1}};
  EXPECT_TRUE(light.sample_li(below, {0.5f, 0.5f}).has_value());
}

// pbrt's "twosided" area lights: the same radiance leaves the back, with the back's irradiance by Lambert's formula.
TEST(MeshLight, TwoSidedEmitsFromBothSides) {
  const std::vector<Vec3f> tri{{-0.5f, -0.4f, 1.0f}, {0.2f, 0.9f, 1.3f}, {0.8f, -0.3f, 0.9f}};  // normal faces down
  const MeshLight light(tri, std::vector<uint32_t>{0, 1, 2}, kRadiance, true);
  EXPECT_TRUE(light.two_sided());
  const Vec3f n = normalize(cross(tri[1] - tri[0], tri[2] - tri[0]));
  EXPECT_EQ(light.emitted(n, -n), kRadiance);
  EXPECT_EQ(light.emitted(n, n), kRadiance);
  for (const LightQuery q : {LightQuery{{0, 0, 0}, {0, 0, 1}}, LightQuery{{0.1f, 0.2f, 3.0f}, {0, 0, -1}},
                             LightQuery{{0.4f, -0.1f, 2.2f}, normalize(Vec3f{0.3f, 0.1f, -1})}}) {
    const double expected = test::polygon_irradiance(tri, q.p, q.n, kL);
    const auto e = irradiance(light, q, 12);
    EXPECT_EQ(e.invalid, 0);
    EXPECT_TRUE(within_error(e, expected)) << e.mean << " +- " << e.std_error << " vs " << expected;
    Rng rng(4, 4);
    for (int i = 0; i < 100; ++i) {
      const auto s = light.sample_li(q, rng.next_2d());
      ASSERT_TRUE(s);
      EXPECT_NEAR(light.pdf_li(q, s->p_light, s->n_light, 0), s->pdf, 1e-3f * s->pdf);
    }
  }
  EXPECT_NEAR(light.power(), 2.0f * make(tri, {0, 1, 2}).power(), 1e-5f);
}

// Disjoint triangles with different areas plus a degenerate one: which triangle each sample lands on must follow
// the area distribution (chi-square), and the degenerate triangle is never chosen.
TEST(MeshLight, PicksTrianglesInProportionToArea) {
  std::vector<Vec3f> p;
  std::vector<uint32_t> idx;
  const std::array<float, 6> sizes{1.0f, 0.3f, 2.0f, 0.0f, 0.7f, 1.4f};  // 0: degenerate
  for (size_t i = 0; i < sizes.size(); ++i) {
    const float x = 10.0f * float(i), s = sizes[i];
    const uint32_t base = uint32_t(p.size());
    // In the plane z = 1 facing down; the degenerate one is three collinear points.
    p.push_back({x, 0, 1});
    p.push_back(s > 0 ? Vec3f{x, s, 1} : Vec3f{x + 1, 0, 1});
    p.push_back(s > 0 ? Vec3f{x + 1.5f * s, 0, 1} : Vec3f{x + 2, 0, 1});
    idx.insert(idx.end(), {base, base + 1, base + 2});
  }
  const MeshLight light = make(p, idx);
  ASSERT_EQ(light.triangle_count(), sizes.size());
  EXPECT_EQ(light.triangle_area(3), 0.0f);
  EXPECT_EQ(light.triangle_pmf(3), 0.0f);

  const LightQuery q{{25, 0.5f, -3}, {0, 0, 1}};
  std::vector<uint64_t> counts(sizes.size(), 0);
  Rng rng(17, 3);
  constexpr int kSamples = 200000;
  for (int k = 0; k < kSamples; ++k) {
    const auto s = light.sample_li(q, rng.next_2d());
    ASSERT_TRUE(s.has_value());
    const size_t tri = size_t(std::lround(s->p_light.x / 10.0f - 0.3f));  // triangles span x in [10i, 10i + 3]
    ASSERT_LT(tri, sizes.size());
    ++counts[tri];
  }
  std::vector<double> expected(sizes.size());
  double total = 0;
  for (float s : sizes) total += 0.75 * s * s;
  for (size_t i = 0; i < sizes.size(); ++i) expected[i] = 0.75 * sizes[i] * sizes[i] / total;
  const auto r = test::chi2_discrete(counts, expected, 0.01);
  EXPECT_TRUE(r.passed) << r.message;
}

// The point within the chosen triangle is uniform: count samples in the four midpoint sub-triangles.
TEST(MeshLight, PointsAreUniformWithinATriangle) {
  const Vec3f a{0, 0, 1}, b{0, 2, 1}, c{3, 0.5f, 1};
  const MeshLight light = make({a, b, c}, {0, 1, 2});
  const LightQuery q{{1, 1, 0}, {0, 0, 1}};
  std::vector<uint64_t> counts(4, 0);
  Rng rng(23, 1);
  for (int k = 0; k < 100000; ++k) {
    const auto s = light.sample_li(q, rng.next_2d());
    ASSERT_TRUE(s.has_value());
    // Barycentrics of p w.r.t. (a, b, c) in the plane z = 1.
    const Vec3f v0 = b - a, v1 = c - a, v2 = s->p_light - a;
    const float d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0), d21 = dot(v2, v1);
    const float den = d00 * d11 - d01 * d01;
    const float bb = (d11 * d20 - d01 * d21) / den, bc = (d00 * d21 - d01 * d20) / den, ba = 1 - bb - bc;
    ++counts[ba > 0.5f ? 0 : bb > 0.5f ? 1 : bc > 0.5f ? 2 : 3];
  }
  const std::vector<double> expected(4, 0.25);
  const auto r = test::chi2_discrete(counts, expected, 0.01);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(MeshLight, PdfLiAgreesWithSampleLi) {
  const std::vector<Vec3f> p{{0, 0, 1}, {0, 1, 1.2f}, {1, 0, 0.9f}, {1, 1, 1.4f}, {2, 0.5f, 1.1f}};
  const std::vector<uint32_t> idx{0, 1, 2, 2, 1, 3, 2, 3, 4};
  const MeshLight light = make(p, idx);
  Rng rng(8, 8);
  int checked = 0;
  for (int k = 0; k < 3000; ++k) {
    const LightQuery q{{2 * rng.next_float() - 0.5f, 2 * rng.next_float() - 0.5f, -rng.next_float()}, {0, 0, 1}};
    const auto s = light.sample_li(q, rng.next_2d());
    if (!s) continue;
    // Find the triangle the point lies on by projecting to the xy plane.
    uint32_t prim = 99;
    for (uint32_t t = 0; t < 3; ++t) {
      const Vec3f a = p[idx[3 * t]], b = p[idx[3 * t + 1]], c = p[idx[3 * t + 2]];
      const auto edge = [](Vec3f u, Vec3f v, Vec3f w) { return (v.x - u.x) * (w.y - u.y) - (v.y - u.y) * (w.x - u.x); };
      const float e0 = edge(a, b, s->p_light), e1 = edge(b, c, s->p_light), e2 = edge(c, a, s->p_light);
      if ((e0 >= -1e-6f && e1 >= -1e-6f && e2 >= -1e-6f) || (e0 <= 1e-6f && e1 <= 1e-6f && e2 <= 1e-6f)) prim = t;
    }
    ASSERT_NE(prim, 99u);
    EXPECT_NEAR(light.pdf_li(q, s->p_light, s->n_light, prim), s->pdf, 1e-4f * s->pdf);
    ++checked;
  }
  EXPECT_GT(checked, 2000);
  EXPECT_EQ(light.pdf_li({{0, 0, 0}, {0, 0, 1}}, {0.2f, 0.2f, 1}, {}, 7), 0.0f);  // no such triangle
}

TEST(MeshLight, PowerIsPiAreaRadiance) {
  const MeshLight light = make({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, {0, 1, 2});
  EXPECT_NEAR(light.power(), kPi * 2.0f * kRadiance.luminance(), 1e-5f);
  const MeshLight degenerate = make({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 1, 2});
  EXPECT_EQ(degenerate.power(), 0.0f);
  EXPECT_FALSE(degenerate.sample_li({{0, 0, 1}, {0, 0, -1}}, {0.5f, 0.5f}).has_value());
}

TEST(MeshLight, RejectsBadIndices) {
  try {
    make({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 3});
    FAIL() << "expected kiln::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex index 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1}), Error);
}

}  // namespace
}  // namespace kiln
