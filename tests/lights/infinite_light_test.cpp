// InfiniteLight (constant radiance from every direction): sampled directions follow pdf_direction (chi-square, with
// and without a normal), irradiance is pi L, samples are consistent with pdf_li and the escaped-ray radiance, and
// bad input is rejected.
#include <gtest/gtest.h>

#include "core/error.h"
#include "light_test_util.h"
#include "lights/infinite_light.h"
#include "support/chi2.h"

namespace kiln {
namespace {

using test::estimate;
using test::irradiance_sample;
using test::within_error;

constexpr float kL = 0.8f;
const Rgb kRadiance{kL};
constexpr float kSceneRadius = 3.0f;
constexpr int kSamples = 200000;
// Four chi-square tests in this file share the significance (Šidák).
constexpr int kChi2Tests = 4;

LightQuery tilted_query() { return {{0.3f, -1.0f, 2.0f}, normalize(Vec3f{0.4f, -0.3f, 0.8f})}; }

test::Chi2Result chi2(const InfiniteLight& light, const LightQuery& q, uint64_t seed) {
  return test::chi2_sphere(
      [&](Rng& rng) -> std::optional<Vec3f> {
        const auto s = light.sample_li(q, rng.next_2d());
        if (!s) return std::nullopt;
        return s->wi;
      },
      [&](Vec3f w) -> double { return light.pdf_direction(q, w); }, 1000000, 20, 40, 0.01, kChi2Tests, seed);
}

TEST(InfiniteLight, CosineSamplingAroundTheNormalMatchesPdfChi2) {
  const InfiniteLight light(kRadiance, kSceneRadius);
  for (const LightQuery& q : {LightQuery{{0, 0, 0}, {0, 0, 1}}, tilted_query(), LightQuery{{1, 2, 3}, {0, -1, 0}}}) {
    const auto r = chi2(light, q, 7);
    EXPECT_TRUE(r.passed) << r.message;
  }
}

TEST(InfiniteLight, UniformSphereSamplingWithoutANormalMatchesPdfChi2) {
  const InfiniteLight light(kRadiance, kSceneRadius);
  const auto r = chi2(light, LightQuery{{0, 0, 0}, {0, 0, 0}}, 8);
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_FLOAT_EQ(light.pdf_direction(LightQuery{{0, 0, 0}, {0, 0, 0}}, {0, 0, -1}), float(1.0 / (4.0 * test::kPiD)));
}

TEST(InfiniteLight, IrradianceIsPiTimesRadiance) {
  const InfiniteLight light(kRadiance, kSceneRadius);
  const LightQuery q = tilted_query();
  const auto e = estimate(
      [&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_li(qq, u); }, q, rng); },
      kSamples, 3);
  EXPECT_EQ(e.invalid, 0);
  EXPECT_TRUE(within_error(e, test::kPiD * kL)) << e.mean << " +- " << e.std_error;
  // Cosine sampling makes the estimate exact sample by sample.
  EXPECT_LT(e.std_error, 1e-4);
}

TEST(InfiniteLight, UniformEstimateOfIrradianceIsUnbiased) {
  // Without a normal in the query the sphere is sampled uniformly; the cosine-weighted estimate still gives pi L.
  const InfiniteLight light(kRadiance, kSceneRadius);
  const Vec3f n = normalize(Vec3f{-0.2f, 0.5f, 0.6f});
  const auto e = estimate(
      [&](Rng& rng) {
        const auto s = light.sample_li(LightQuery{{0, 0, 0}, {0, 0, 0}}, rng.next_2d());
        return s ? double(s->li.g) * std::max(0.0f, dot(n, s->wi)) / double(s->pdf) : 0.0;
      },
      kSamples, 4);
  EXPECT_TRUE(within_error(e, test::kPiD * kL)) << e.mean << " +- " << e.std_error;
}

TEST(InfiniteLight, SamplesAgreeWithPdfLiAndEscapedRadiance) {
  const InfiniteLight light(Rgb(0.2f, 0.5f, 1.5f), kSceneRadius);
  const LightQuery q = tilted_query();
  Rng rng(11, 3);
  for (int i = 0; i < 1000; ++i) {
    const auto s = light.sample_li(q, rng.next_2d());
    ASSERT_TRUE(s);
    EXPECT_NEAR(length(s->wi), 1.0f, 1e-5f);
    EXPECT_GE(dot(s->wi, q.n), 0.0f);
    EXPECT_FALSE(s->delta);
    EXPECT_EQ(s->li, Rgb(0.2f, 0.5f, 1.5f));
    EXPECT_EQ(light.radiance(s->wi), s->li);
    EXPECT_NEAR(s->distance, 2.0f * kSceneRadius, 1e-5f);
    EXPECT_NEAR(light.pdf_li(q, s->p_light, {}, 0), s->pdf, 1e-4f * s->pdf + 1e-6f);
    EXPECT_NEAR(light.pdf_direction(q, s->wi), s->pdf, 1e-4f * s->pdf + 1e-6f);
  }
  // Below the surface the light strategy has no density (BSDF sampling covers those directions).
  EXPECT_EQ(light.pdf_direction(q, -q.n), 0.0f);
}

TEST(InfiniteLight, PowerIsPbrtsFluxThroughTheSceneDisk) {
  const InfiniteLight light(kRadiance, kSceneRadius);
  EXPECT_NEAR(light.power(), 4.0 * test::kPiD * test::kPiD * kSceneRadius * kSceneRadius * kRadiance.luminance(), 1e-3);
  EXPECT_FALSE(InfiniteLight::kDelta);
}

TEST(InfiniteLight, RejectsBadInput) {
  EXPECT_THROW(InfiniteLight(Rgb(-1.0f), 1.0f), Error);
  EXPECT_THROW(InfiniteLight(Rgb(std::numeric_limits<float>::infinity()), 1.0f), Error);
  EXPECT_THROW(InfiniteLight(kRadiance, 0.0f), Error);
}

}  // namespace
}  // namespace kiln
