// AreaLight (the course's invisible square / parallelogram): irradiance against Lambert's polygon formula on both
// sides, uniform area sampling, pdf consistency and the "cannot be hit" contract.
#include <gtest/gtest.h>

#include "core/error.h"
#include "light_test_util.h"
#include "lights/area_light.h"
#include "support/chi2.h"

namespace kiln {
namespace {

using test::estimate;
using test::irradiance_sample;
using test::within_error;

constexpr float kL = 3.0f;
const Rgb kRadiance{kL};
constexpr int kIrradianceSamples = 200000;

std::vector<Vec3f> corners(const AreaLight& a) {
  return {a.corner(), a.corner() + a.edge1(), a.corner() + a.edge1() + a.edge2(), a.corner() + a.edge2()};
}

test::Estimate irradiance(const AreaLight& light, const LightQuery& q, uint64_t seed) {
  return estimate([&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_li(qq, u); }, q, rng); },
                  kIrradianceSamples, seed);
}

TEST(AreaLight, SquareGeometry) {
  const AreaLight a = AreaLight::square({1, 2, 3}, {0, 0, -2}, 1.5f, kRadiance);
  EXPECT_NEAR(a.area(), 2.25f, 1e-5f);
  EXPECT_NEAR(dot(a.normal(), Vec3f(0, 0, -1)), 1.0f, 1e-6f);
  const Vec3f centre = a.corner() + (a.edge1() + a.edge2()) * 0.5f;
  EXPECT_NEAR(length(centre - Vec3f(1, 2, 3)), 0.0f, 1e-6f);
  EXPECT_NEAR(length(a.edge1()), 1.5f, 1e-6f);
  EXPECT_NEAR(dot(a.edge1(), a.edge2()), 0.0f, 1e-6f);
}

// Two-sided: the same irradiance on either side of the light (mirror-image receivers).
TEST(AreaLight, SquareIrradianceMatchesLambertFormulaOnBothSides) {
  const AreaLight light = AreaLight::square({0.2f, -0.1f, 2.0f}, normalize(Vec3f{0.1f, 0.3f, -1}), 1.2f, kRadiance);
  for (const LightQuery q : {LightQuery{{0, 0, 0}, {0, 0, 1}}, LightQuery{{0.5f, 0.3f, 0.5f}, normalize(Vec3f{-0.2f, 0.1f, 1})},
                             LightQuery{{0.1f, 0.0f, 4.0f}, {0, 0, -1}}}) {
    const double expected = test::polygon_irradiance(corners(light), q.p, q.n, kL);
    const auto e = irradiance(light, q, 3);
    EXPECT_EQ(e.invalid, 0);
    EXPECT_GT(expected, 0.0);
    EXPECT_TRUE(within_error(e, expected)) << "q=(" << q.p.x << "," << q.p.y << "," << q.p.z << "): " << e.mean
                                           << " +- " << e.std_error << " vs " << expected;
  }
}

TEST(AreaLight, ParallelogramIrradianceMatchesLambertFormula) {
  const AreaLight light = AreaLight::parallelogram({-1, -0.5f, 1.5f}, {2, 0.3f, 0}, {0.7f, 1.2f, 0.4f}, kRadiance);
  const LightQuery q{{0.3f, 0.2f, 0}, normalize(Vec3f{0.1f, -0.1f, 1})};
  const double expected = test::polygon_irradiance(corners(light), q.p, q.n, kL);
  const auto e = irradiance(light, q, 4);
  EXPECT_TRUE(within_error(e, expected)) << e.mean << " +- " << e.std_error << " vs " << expected;
  EXPECT_NEAR(light.area(), length(cross(Vec3f{2, 0.3f, 0}, Vec3f{0.7f, 1.2f, 0.4f})), 1e-5f);
}

// Uniform in area: a 4 x 4 grid over the parallelogram's (a, b) coordinates.
TEST(AreaLight, SamplesAreUniformOverTheSurface) {
  const AreaLight light = AreaLight::parallelogram({0, 0, 1}, {2, 0, 0}, {0.5f, 1, 0}, kRadiance);
  const LightQuery q{{0.5f, 0.5f, 0}, {0, 0, 1}};
  std::vector<uint64_t> counts(16, 0);
  Rng rng(5, 6);
  for (int k = 0; k < 160000; ++k) {
    const auto s = light.sample_li(q, rng.next_2d());
    ASSERT_TRUE(s.has_value());
    const float b = s->p_light.y, a = (s->p_light.x - 0.5f * b) / 2.0f;  // invert corner + a e1 + b e2
    ASSERT_NEAR(s->p_light.z, 1.0f, 1e-6f);
    const int ia = std::clamp(int(a * 4), 0, 3), ib = std::clamp(int(b * 4), 0, 3);
    ++counts[size_t(ia * 4 + ib)];
  }
  const std::vector<double> expected(16, 1.0 / 16);
  const auto r = test::chi2_discrete(counts, expected, 0.01);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(AreaLight, SamplesAreFlaggedUnhittableWithARealDensity) {
  const AreaLight light = AreaLight::square({0, 0, 2}, {0, 0, -1}, 1.0f, kRadiance);
  Rng rng(1, 2);
  for (int k = 0; k < 1000; ++k) {
    const LightQuery q{{rng.next_float() - 0.5f, rng.next_float() - 0.5f, 4 * rng.next_float()}, {0, 0, 1}};
    const auto s = light.sample_li(q, rng.next_2d());
    if (!s) continue;
    EXPECT_TRUE(s->delta);
    EXPECT_EQ(s->li, kRadiance);
    const float d = length(s->p_light - q.p);
    EXPECT_NEAR(s->pdf, d * d / (absdot(s->wi, light.normal()) * light.area()), 1e-4f * s->pdf);
    EXPECT_NEAR(light.pdf_li(q, s->p_light, s->n_light, 0), s->pdf, 1e-4f * s->pdf);
  }
  EXPECT_TRUE(light.emitted({0, 0, -1}, {0, 0, -1}).is_black());
  EXPECT_NEAR(light.power(), 2 * kPi * 1.0f * kRadiance.luminance(), 1e-5f);
  // A receiver in the light's plane sees nothing.
  EXPECT_FALSE(light.sample_li({{3, 0, 2}, {-1, 0, 0}}, {0.5f, 0.5f}).has_value());
}

TEST(AreaLight, RejectsDegenerateInput) {
  EXPECT_THROW(AreaLight::square({0, 0, 0}, {0, 0, 1}, 0.0f, kRadiance), Error);
  EXPECT_THROW(AreaLight::square({0, 0, 0}, {0, 0, 0}, 1.0f, kRadiance), Error);
  EXPECT_THROW(AreaLight::parallelogram({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, kRadiance), Error);
}

}  // namespace
}  // namespace kiln
