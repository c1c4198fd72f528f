// Point, spot and directional lights: inverse-square law, the spot's full-angle cone and s^4 falloff, the
// directional light's far-away shadow target, and their power estimates.
#include <gtest/gtest.h>

#include "core/error.h"
#include "light_test_util.h"
#include "lights/directional_light.h"
#include "lights/point_light.h"
#include "lights/spot_light.h"
#include "support/chi2.h"

namespace kiln {
namespace {

const Rgb kI{1.0f, 2.0f, 3.0f};

TEST(PointLight, InverseSquareLaw) {
  const PointLight light({1, 2, 3}, kI);
  const LightQuery q{{1, 2, 0}, {0, 0, 1}};
  const auto s = light.sample_li(q, {0.3f, 0.7f});
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->li.b, 3.0f / 9.0f, 1e-6f);
  EXPECT_NEAR(s->wi.z, 1.0f, 1e-6f);
  EXPECT_EQ(s->p_light, Vec3f(1, 2, 3));
  EXPECT_NEAR(s->distance, 3.0f, 1e-6f);
  EXPECT_EQ(s->pdf, 1.0f);
  EXPECT_TRUE(s->delta);
  EXPECT_EQ(light.pdf_li(q, s->p_light, s->n_light, 0), 0.0f);
  EXPECT_TRUE(light.emitted({0, 0, 1}, {0, 0, 1}).is_black());
  EXPECT_NEAR(light.power(), 4 * kPi * kI.luminance(), 1e-5f);
  EXPECT_FALSE(light.sample_li({{1, 2, 3}, {0, 0, 1}}, {0, 0}).has_value());  // at the light itself
}

// Coverage 60 and falloff 20 degrees are FULL angles: full intensity up to 10 degrees off the axis, nothing past
// 30 degrees, s^4 in between.
TEST(SpotLight, FullConeAnglesAndQuarticFalloff) {
  const SpotLight light({0, 0, 0}, {0, 0, -2}, kI, 60.0f, 20.0f);
  const auto li_at = [&](float angle_deg) -> float {
    const float a = radians(angle_deg);
    const LightQuery q{{2 * std::sin(a), 0, -2 * std::cos(a)}, {0, 0, 1}};
    const auto s = light.sample_li(q, {0.5f, 0.5f});
    return s ? s->li.r * 4.0f : 0.0f;  // undo 1/d^2
  };
  EXPECT_NEAR(li_at(0), 1.0f, 1e-5f);
  EXPECT_NEAR(li_at(9.9f), 1.0f, 1e-5f);
  EXPECT_EQ(li_at(30.5f), 0.0f);
  EXPECT_EQ(li_at(45.0f), 0.0f);
  const float cos_cov = std::cos(radians(30)), cos_fall = std::cos(radians(10));
  for (float angle : {12.0f, 20.0f, 28.0f}) {
    const float s = (std::cos(radians(angle)) - cos_cov) / (cos_fall - cos_cov);
    EXPECT_NEAR(li_at(angle), s * s * s * s, 1e-4f) << angle;
  }
  EXPECT_FALSE(light.sample_li({{0, 0, 2}, {0, 0, 1}}, {0, 0}).has_value());  // behind the spot
}

TEST(SpotLight, PowerIsTheIntegralOfTheFalloff) {
  const SpotLight light({0, 0, 0}, {0.3f, -1, 0.2f}, kI, 90.0f, 40.0f);
  const double numeric = test::integrate_sphere([&](Vec3f w) { return double(light.falloff(w)); }, 1024, 2048);
  EXPECT_NEAR(light.power(), numeric * kI.luminance(), 2e-3 * numeric * kI.luminance());
  // Falloff wider than coverage: a hard-edged cone of half-angle 15 degrees.
  const SpotLight hard({0, 0, 0}, {0, 0, 1}, kI, 30.0f, 50.0f);
  EXPECT_NEAR(hard.power(), 2 * kPi * (1 - std::cos(radians(15))) * kI.luminance(), 1e-5f);
  EXPECT_THROW(SpotLight(Vec3f{0, 0, 0}, Vec3f{0, 0, 0}, kI, 30.0f, 10.0f), Error);
}

// pbrt-v4's spot light: smoothstep(s) = s^2 (3 - 2 s) across the ring instead of s^4, and its flux.
TEST(SpotLight, SmoothStepFalloffAndPower) {
  const SpotLight light({0, 0, 0}, {0, 0, 1}, kI, 60.0f, 20.0f, true);
  const float cos_cov = std::cos(radians(30)), cos_fall = std::cos(radians(10));
  EXPECT_NEAR(light.falloff({0, 0, 1}), 1.0f, 1e-6f);
  for (float angle : {12.0f, 20.0f, 28.0f}) {
    const float a = radians(angle);
    const float s = (std::cos(a) - cos_cov) / (cos_fall - cos_cov);
    EXPECT_NEAR(light.falloff({std::sin(a), 0, std::cos(a)}), s * s * (3 - 2 * s), 1e-4f) << angle;
  }
  EXPECT_EQ(light.falloff({std::sin(radians(31)), 0, std::cos(radians(31))}), 0.0f);
  const double numeric = test::integrate_sphere([&](Vec3f w) { return double(light.falloff(w)); }, 1024, 2048);
  EXPECT_NEAR(light.power(), numeric * kI.luminance(), 2e-3 * numeric * kI.luminance());
}

TEST(DirectionalLight, ConstantIrradianceAndFarTarget) {
  const DirectionalLight light({1, -0.8f, -1}, Rgb(200.0f), 50.0f);
  const LightQuery q{{3, 4, 5}, {0, 1, 0}};
  const auto s = light.sample_li(q, {0.1f, 0.9f});
  ASSERT_TRUE(s.has_value());
  const Vec3f wi = -normalize(Vec3f{1, -0.8f, -1});
  EXPECT_NEAR(length(s->wi - wi), 0.0f, 1e-6f);
  EXPECT_EQ(s->li, Rgb(200.0f));
  EXPECT_NEAR(length(s->p_light - (q.p + wi * 100.0f)), 0.0f, 1e-4f);
  EXPECT_NEAR(s->distance, 100.0f, 1e-4f);
  EXPECT_EQ(s->pdf, 1.0f);
  EXPECT_TRUE(s->delta);
  EXPECT_NEAR(light.power(), kPi * 2500.0f * 200.0f, 1.0f);
  EXPECT_THROW(DirectionalLight(Vec3f{0, 0, 0}, Rgb(1.0f), 1.0f), Error);
}

}  // namespace
}  // namespace kiln
