// ImageInfiniteLight (environment maps, lat-long and pbrt-v4's equal-area square): importance-sampled directions
// follow pdf_direction (chi-square) and the pdf integrates to 1, for the equal-area layout also under a rotated and
// under a sheared placement (whose solid-angle Jacobian enters the density); the course's uniform hemisphere too;
// samples agree with pdf_li and the escaped radiance; a constant map gives irradiance pi L; the lat-long mapping
// round-trips; bad input is rejected.
#include <gtest/gtest.h>

#include "core/equal_area.h"
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
constexpr int kChi2Tests = 6;  // chi-square tests in this file (Šidák)
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

// Samples from a tilted query: unit directions carrying the escaped radiance, at the shadow-target distance, with the
// density pdf_li and pdf_direction give them.
void expect_samples_agree(const ImageInfiniteLight& light, uint64_t seed) {
  const LightQuery q{{0.3f, -1.0f, 2.0f}, normalize(Vec3f{0.4f, -0.3f, 0.8f})};
  Rng rng(seed, 3);
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

// The one-sample irradiance estimate at a tilted normal (a constant map L gives pi L).
test::Estimate irradiance(const ImageInfiniteLight& light) {
  const LightQuery q{{0, 0, 0}, normalize(Vec3f{-0.2f, 0.5f, 0.6f})};
  return estimate(
      [&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_li(qq, u); }, q, rng); },
      400000, 3);
}

TEST(ImageInfiniteLight, SamplesAgreeWithPdfLiAndEscapedRadiance) {
  for (EnvMapSampling mode : {EnvMapSampling::ImportanceSampled, EnvMapSampling::UniformHemisphere})
    expect_samples_agree(ImageInfiniteLight(test_map(), kSceneRadius, mode), 11);
}

TEST(ImageInfiniteLight, ConstantMapGivesIrradiancePiL) {
  constexpr float kL = 0.7f;
  Image img(kW, kH);
  for (Rgb& c : img.pixels()) c = Rgb(kL);
  for (EnvMapSampling mode : {EnvMapSampling::ImportanceSampled, EnvMapSampling::UniformHemisphere}) {
    const auto e = irradiance(ImageInfiniteLight(img, kSceneRadius, mode));
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

// An equal-area map with a sun, a gradient and a black quadrant (the square's corners are the -z pole).
constexpr int kSquare = 16;
Image square_map() {
  Image img(kSquare, kSquare);
  for (int y = 0; y < kSquare; ++y)
    for (int x = 0; x < kSquare; ++x) img.at(x, y) = Rgb(0.05f + 0.1f * float(x), 0.2f, 0.02f * float(y + 1));
  for (int y = 0; y < kSquare / 2; ++y)
    for (int x = 0; x < kSquare / 2; ++x) img.at(x, y) = Rgb(0.0f);
  img.at(11, 6) = Rgb(40.0f, 30.0f, 20.0f);
  return img;
}

// Placements of the map's frame: none, a rotation, and a shear with a mirror (a general linear map).
std::vector<std::pair<const char*, EnvMapPlacement>> equal_area_placements() {
  Mat4 shear = Mat4::identity();
  shear.m[0] = {1.0f, 0.4f, 0.0f, 0.0f};
  shear.m[1] = {0.0f, -0.8f, 0.3f, 0.0f};
  shear.m[2] = {0.2f, 0.0f, 1.3f, 0.0f};
  return {{"identity", {EnvMapLayout::EqualArea, Transform()}},
          {"rotated", {EnvMapLayout::EqualArea, Transform::rotate(-70.0f, normalize(Vec3f(1, 0.5f, 0.2f)))}},
          {"sheared", {EnvMapLayout::EqualArea, Transform::from_matrix(shear)}}};
}

TEST(ImageInfiniteLight, EqualAreaSamplingMatchesPdfChi2) {
  const LightQuery q{{0.3f, -1.0f, 2.0f}, normalize(Vec3f{0.4f, -0.3f, 0.8f})};
  uint64_t seed = 21;
  for (const auto& [name, placement] : equal_area_placements()) {
    const ImageInfiniteLight light(square_map(), kSceneRadius, EnvMapSampling::ImportanceSampled, placement);
    const auto r = test::chi2_sphere(
        [&](Rng& rng) -> std::optional<Vec3f> {
          const auto s = light.sample_li(q, rng.next_2d());
          if (!s) return std::nullopt;
          return s->wi;
        },
        [&](Vec3f w) -> double { return light.pdf_direction(q, w); }, 1000000, 24, 48, 0.01, kChi2Tests, seed++);
    EXPECT_TRUE(r.passed) << name << ": " << r.message;
  }
}

TEST(ImageInfiniteLight, EqualAreaPdfIntegratesToOneAndFollowsRadiance) {
  const LightQuery q{{0, 0, 0}, {0, 0, 1}};
  for (const auto& [name, placement] : equal_area_placements()) {
    const ImageInfiniteLight light(square_map(), kSceneRadius, EnvMapSampling::ImportanceSampled, placement);
    const double integral = test::integrate_sphere([&](Vec3f w) { return light.pdf_direction(q, w); }, 1024, 2048);
    EXPECT_NEAR(integral, 1.0, 2e-3) << name;
  }
  // Unplaced, the density is luminance / (total luminance * 4 pi / texels): the sun texel's and a dim texel's.
  const Image map = square_map();
  const ImageInfiniteLight light(map, kSceneRadius, EnvMapSampling::ImportanceSampled,
                                 {EnvMapLayout::EqualArea, Transform()});
  double total = 0.0;
  for (const Rgb& c : map.pixels()) total += c.luminance();
  for (const auto& [x, y] : {std::pair{11, 6}, std::pair{13, 14}}) {
    const Vec3f d = equal_area_square_to_sphere({(float(x) + 0.5f) / kSquare, (float(y) + 0.5f) / kSquare});
    const double expected = map.at(x, y).luminance() / total * (kSquare * kSquare) / (4.0 * test::kPiD);
    EXPECT_NEAR(light.pdf_direction(q, d), expected, 1e-4 * expected) << x << " " << y;
    EXPECT_EQ(light.radiance(d), map.at(x, y));
  }
  EXPECT_EQ(light.pdf_direction(q, equal_area_square_to_sphere({0.2f, 0.3f})), 0.0f);  // the black quadrant
}

TEST(ImageInfiniteLight, EqualAreaSamplesAgreeWithPdfLiAndRadianceUnderAPlacement) {
  const auto placement = equal_area_placements()[1].second;
  const ImageInfiniteLight light(square_map(), kSceneRadius, EnvMapSampling::ImportanceSampled, placement);
  expect_samples_agree(light, 12);
  // The map's +z (its centre texel) is where the placement sends it.
  const Vec3f up = placement.light_to_world.vector({0, 0, 1});
  EXPECT_EQ(light.radiance(normalize(up)), square_map().at(kSquare / 2, kSquare / 2));
}

TEST(ImageInfiniteLight, ConstantEqualAreaMapGivesIrradiancePiL) {
  constexpr float kL = 0.7f;
  Image img(kSquare, kSquare);
  for (Rgb& c : img.pixels()) c = Rgb(kL);
  const ImageInfiniteLight light(img, kSceneRadius, EnvMapSampling::ImportanceSampled,
                                 equal_area_placements()[1].second);
  const auto e = irradiance(light);
  EXPECT_EQ(e.invalid, 0);
  EXPECT_TRUE(within_error(e, test::kPiD * kL)) << e.mean << " +- " << e.std_error;
  EXPECT_NEAR(light.power(), 4.0 * test::kPiD * test::kPiD * kSceneRadius * kSceneRadius * kL, 1e-2);
}

TEST(ImageInfiniteLight, EqualAreaLookupsBeyondTheSquareWrapOctahedrally) {
  // A direction on the square's right edge has u = 1: the nearest texel index is one past the last column, and
  // folds back onto the last column with the row mirrored, i.e. onto a texel that touches the same edge point.
  Image img(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) img.at(x, y) = Rgb(float(1 + x + 4 * y));
  const ImageInfiniteLight light(img, kSceneRadius, EnvMapSampling::ImportanceSampled,
                                 {EnvMapLayout::EqualArea, Transform()});
  const Vec3f d = normalize(Vec3f(0.6f, 0.0f, -0.8f));  // y = 0, x > 0: the right edge's great circle
  const Vec2f uv = light.map_coordinates(d);
  ASSERT_EQ(uv.x, 1.0f);
  const int row = int(uv.y * 4.0f);
  EXPECT_EQ(light.radiance(d), img.at(3, 3 - row)) << uv.y;
}

TEST(ImageInfiniteLight, RejectsBadInput) {
  EXPECT_THROW(ImageInfiniteLight(Image(), 1.0f), Error);
  EXPECT_THROW(ImageInfiniteLight(test_map(), 0.0f), Error);
  // An equal-area map must be square; a placement must be invertible.
  EXPECT_THROW(ImageInfiniteLight(test_map(), 1.0f, EnvMapSampling::ImportanceSampled,
                                  {EnvMapLayout::EqualArea, Transform()}),
               Error);
  EXPECT_THROW(ImageInfiniteLight(square_map(), 1.0f, EnvMapSampling::ImportanceSampled,
                                  {EnvMapLayout::EqualArea, Transform(Mat4{}, Mat4{})}),
               Error);
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
