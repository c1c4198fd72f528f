// ImageInfiniteLight (lat-long environment map): importance-sampled directions follow pdf_direction (chi-square) and
// the pdf integrates to 1; the course's uniform hemisphere too; samples agree with pdf_li and the escaped radiance;
// a constant map gives irradiance pi L; the lat-long mapping round-trips; bad input is rejected.
#include <gtest/gtest.h>

#include "core/error.h"
#include "light_test_util.h"
#include "lights/image_infinite_light.h"
#include "support/chi2.h"

namespace kiln {
namespace {

using test::estimate;
using test::irradiance_sample;
using test::within_error;

constexpr float kSceneRadius = 3.0f;
constexpr int kChi2Tests = 3;  // chi-square tests in this file (Šidák)
// Map size: the chi-square grid below aligns its cells with the texels (W divisible by 4, see to_chi2_frame).
constexpr int kW = 16, kH = 8;

// A map with a bright "sun" texel, a dim gradient and a black band: strongly non-uniform, with zero-density texels.
Image test_map() {
  Image img(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) img.at(x, y) = Rgb(0.05f + 0.1f * float(x), 0.2f, 0.02f * float(y + 1));
  for (int x = 0; x < kW; ++x) img.at(x, 5) = Rgb(0.0f);
  img.at(11, 2) = Rgb(40.0f, 30.0f, 20.0f);
  return img;
}

// The chi-square helper bins theta from +z; the map's pole is +y. A proper rotation (x, y, z) -> (x, -z, y) puts the
// map's rows on the helper's theta bins and its columns on its phi bins.
Vec3f to_chi2_frame(Vec3f d) { return {d.x, -d.z, d.y}; }
Vec3f from_chi2_frame(Vec3f w) { return {w.x, w.z, -w.y}; }

test::Chi2Result chi2(const ImageInfiniteLight& light, const LightQuery& q, uint64_t seed) {
  return test::chi2_sphere(
      [&](Rng& rng) -> std::optional<Vec3f> {
        const auto s = light.sample_li(q, rng.next_2d());
        if (!s) return std::nullopt;
        return to_chi2_frame(s->wi);
      },
      [&](Vec3f w) -> double { return light.pdf_direction(q, from_chi2_frame(w)); }, 1000000, 2 * kH, 2 * kW, 0.01,
      kChi2Tests, seed);
}

TEST(ImageInfiniteLight, ImportanceSamplingMatchesPdfChi2) {
  // The chi-square helper integrates each cell's expected count by quadrature, which cannot resolve the density's
  // integrable 1/sin(theta) growth towards a lit pole (the pdf test below covers it); the poles' rows are dark here.
  Image map = test_map();
  for (int x = 0; x < kW; ++x) map.at(x, 0) = map.at(x, kH - 1) = Rgb(0.0f);
  const ImageInfiniteLight light(map, kSceneRadius);
  const auto r = chi2(light, LightQuery{{0.3f, -1.0f, 2.0f}, normalize(Vec3f{0.4f, -0.3f, 0.8f})}, 5);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(ImageInfiniteLight, ImportancePdfIntegratesToOne) {
  const ImageInfiniteLight light(test_map(), kSceneRadius);
  const LightQuery q{{0, 0, 0}, {0, 0, 1}};
  const double integral = test::integrate_sphere([&](Vec3f w) { return light.pdf_direction(q, w); }, 1024, 2048);
  EXPECT_NEAR(integral, 1.0, 2e-3);
}

TEST(ImageInfiniteLight, ImportanceDensityIsProportionalToRadiance) {
  // Within a texel row the density is luminance-proportional: the ratio pdf / luminance is the same for every lit
  // texel of the row (the sin theta factor only varies between rows).
  const ImageInfiniteLight light(test_map(), kSceneRadius);
  const LightQuery q{{0, 0, 0}, {0, 0, 1}};
  const float v = (2.0f + 0.5f) / kH;
  const Vec3f sun = ImageInfiniteLight::direction((11.0f + 0.5f) / kW, v);
  const Vec3f dim = ImageInfiniteLight::direction((3.0f + 0.5f) / kW, v);
  EXPECT_NEAR(light.pdf_direction(q, sun) / light.radiance(sun).luminance(),
              light.pdf_direction(q, dim) / light.radiance(dim).luminance(), 1e-4);
  EXPECT_EQ(light.pdf_direction(q, ImageInfiniteLight::direction(0.3f, (5.0f + 0.5f) / kH)), 0.0f);  // black row
}

TEST(ImageInfiniteLight, CourseUniformHemisphereMatchesPdfChi2) {
  const ImageInfiniteLight light(test_map(), kSceneRadius, EnvMapSampling::UniformHemisphere);
  const auto r = chi2(light, LightQuery{{1, 2, 3}, normalize(Vec3f{0.2f, 0.9f, -0.3f})}, 6);
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_FLOAT_EQ(light.pdf_direction(LightQuery{{}, {0, 0, 1}}, {0, 0, 1}), float(1.0 / (2.0 * test::kPiD)));
  EXPECT_EQ(light.pdf_direction(LightQuery{{}, {0, 0, 1}}, {0, 0, -1}), 0.0f);
}

TEST(ImageInfiniteLight, SamplesAgreeWithPdfLiAndEscapedRadiance) {
  for (EnvMapSampling mode : {EnvMapSampling::ImportanceSampled, EnvMapSampling::UniformHemisphere}) {
    const ImageInfiniteLight light(test_map(), kSceneRadius, mode);
    const LightQuery q{{0.3f, -1.0f, 2.0f}, normalize(Vec3f{0.4f, -0.3f, 0.8f})};
    Rng rng(11, 3);
    for (int i = 0; i < 2000; ++i) {
      const auto s = light.sample_li(q, rng.next_2d());
      if (!s) continue;
      EXPECT_NEAR(length(s->wi), 1.0f, 1e-5f);
      EXPECT_FALSE(s->delta);
      EXPECT_EQ(light.radiance(s->wi), s->li);
      EXPECT_NEAR(s->distance, 2.0f * kSceneRadius, 1e-5f);
      EXPECT_NEAR(light.pdf_li(q, s->p_light, {}, 0), s->pdf, 1e-3f * s->pdf);
      EXPECT_NEAR(light.pdf_direction(q, s->wi), s->pdf, 1e-5f * s->pdf);
    }
  }
}

TEST(ImageInfiniteLight, ConstantMapGivesIrradiancePiL) {
  constexpr float kL = 0.7f;
  Image img(kW, kH);
  for (Rgb& c : img.pixels()) c = Rgb(kL);
  for (EnvMapSampling mode : {EnvMapSampling::ImportanceSampled, EnvMapSampling::UniformHemisphere}) {
    const ImageInfiniteLight light(img, kSceneRadius, mode);
    const LightQuery q{{0, 0, 0}, normalize(Vec3f{-0.2f, 0.5f, 0.6f})};
    const auto e = estimate(
        [&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_li(qq, u); }, q, rng); },
        400000, 3);
    EXPECT_EQ(e.invalid, 0);
    EXPECT_TRUE(within_error(e, test::kPiD * kL)) << int(mode) << ": " << e.mean << " +- " << e.std_error;
  }
  // The power estimate is pi r^2 times the integral of L over the sphere, as for the constant InfiniteLight.
  const ImageInfiniteLight light(img, kSceneRadius);
  EXPECT_NEAR(light.power(), 4.0 * test::kPiD * test::kPiD * kSceneRadius * kSceneRadius * kL, 1e-2);
}

TEST(ImageInfiniteLight, LatLongMappingRoundTrips) {
  // The course's convention: +y is v = 0 (top row), -z is u = 1/2.
  EXPECT_NEAR(ImageInfiniteLight::lat_long({0, 1, 0}).y, 0.0f, 1e-6f);
  EXPECT_NEAR(ImageInfiniteLight::lat_long({0, -1, 0}).y, 1.0f, 1e-6f);
  EXPECT_NEAR(ImageInfiniteLight::lat_long({0, 0, -1}).x, 0.5f, 1e-6f);
  EXPECT_NEAR(ImageInfiniteLight::lat_long({1, 0, 0}).x, 0.75f, 1e-6f);
  Rng rng(3, 4);
  for (int i = 0; i < 1000; ++i) {
    const Vec2f uv{rng.next_float(), 0.01f + 0.98f * rng.next_float()};
    const Vec2f back = ImageInfiniteLight::lat_long(ImageInfiniteLight::direction(uv.x, uv.y));
    EXPECT_NEAR(back.x, uv.x, 1e-5f);
    EXPECT_NEAR(back.y, uv.y, 1e-5f);
  }
}

TEST(ImageInfiniteLight, RejectsBadInput) {
  EXPECT_THROW(ImageInfiniteLight(Image(), 1.0f), Error);
  EXPECT_THROW(ImageInfiniteLight(test_map(), 0.0f), Error);
  // Negative and non-finite texels emit nothing (and are never sampled).
  Image img(2, 2);
  img.at(0, 0) = Rgb(-1.0f);
  img.at(1, 0) = Rgb(std::numeric_limits<float>::infinity());
  img.at(0, 1) = Rgb(1.0f);
  const ImageInfiniteLight light(img, 1.0f);
  EXPECT_EQ(light.radiance(ImageInfiniteLight::direction(0.25f, 0.25f)), Rgb(0.0f));
  EXPECT_EQ(light.radiance(ImageInfiniteLight::direction(0.75f, 0.25f)), Rgb(0.0f));
}

}  // namespace
}  // namespace kiln
