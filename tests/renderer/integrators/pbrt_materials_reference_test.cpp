// Kiln against pbrt-v4 on ../shared/scenes/pbrt/features/materials.pbrt: three killeroos in coatedconductor (gold,
// named metal spectra), diffusetransmission and a mix of a red diffuse and a blue rough conductor given by
// reflectance; a thindielectric pane; a disk light and a sphere light with blackbody L (3500 K). pbrt-v4's render
// (reference/materials.exr) has 256 spp; Kiln renders the file as `kiln render` does at 16 spp and is held to the
// issue's limits over 16-px blocks (luminance median < 2%, p95 < 8%, mean ratio within 2%), over the whole image and
// over the killeroos' region.
//
// Noise: two Kiln seeds at 16 spp differ by a block p95 of 4.0% over the whole image (median 0.35%), most of it in
// the pane's caustic band, and by less over the killeroos; against pbrt's 256-spp image Kiln measures p95 3.0-3.4%
// (whole image) and 1.3-2.1% (killeroos), mean ratios 0.998-0.999 and 0.997-0.998. The limits are the issue's: the
// noise at 16 spp leaves them a margin of twice the measured values, so no limit needed widening.
//
// What remains is measured, not tuned away: the gold killeroo is ~0.7% darker (its block mean ratio 0.992-0.994, its
// mean colour 0.995 / 0.990 / 1.003).
// pbrt's spectral gold is redder than any RGB conductor can be: lit by D65 its reflectance has an sRGB red of 1.02 at
// normal incidence (the spectrum's colour lies outside the sRGB gamut), where a Fresnel reflectance per channel
// stays below 1 (scenes/pbrt/spectrum.h fits gold's eta and k to 0.995).
#include <gtest/gtest.h>

#include "renderer/pbrt_reference_util.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

constexpr uint32_t kSpp = 16;
constexpr double kMeanLimit = 0.02;  // per channel of each killeroo's mean colour, as the mean ratio's limit
// Regions of the 600x400 image, on the 16-px block grid: the three killeroos together and each one alone.
struct Region {
  const char* name;
  PixelRect rect;
};
constexpr Region kKilleroos{"killeroos", {80, 112, 592, 256}};
constexpr Region kEachKilleroo[] = {{"mix killeroo", {80, 112, 192, 240}},
                                    {"diffusetransmission killeroo", {248, 112, 392, 240}},
                                    {"coatedconductor killeroo", {408, 112, 600, 240}}};

Rgb mean_rgb(const Image& img) {
  double s[3] = {0, 0, 0};
  for (const Rgb& p : img.pixels())
    for (int c = 0; c < 3; ++c) s[c] += p[c];
  const double n = double(img.pixels().size());
  return {float(s[0] / n), float(s[1] / n), float(s[2] / n)};
}


TEST(PbrtReference, MaterialsFeatureSceneMatchesPbrtV4) {
  KILN_NEED_SHARED_PATH(feature_scene("materials.pbrt"));
  const SceneDesc scene = load_scene(feature_scene("materials.pbrt"));
  const auto world = build_scene_world(scene);
  ASSERT_TRUE(world->features & kFeatureMix);
  ASSERT_TRUE(world->features & kFeatureQuadricLights) << "the disk light";
  const Image image = render_like_kiln(scene, *world, kSpp, 1);
  const Image reference = read_exr(feature_scene("reference/materials.exr")).rgb;
  ASSERT_EQ(image.width(), reference.width());
  ASSERT_EQ(image.height(), reference.height());
  const std::string name = "materials.pbrt, " + std::to_string(kSpp) + " spp, ";
  expect_within_feature_limits(blocks_against_reference(name + "whole image", image, reference), "whole image");
  expect_within_feature_limits(blocks_against_reference(name + kKilleroos.name, image, reference, kKilleroos.rect),
                       kKilleroos.name);
  for (const Region& k : kEachKilleroo) {
    expect_within_feature_limits(blocks_against_reference(name + k.name, image, reference, k.rect), k.name);
    const Rgb ratio = mean_rgb(cropped(image, k.rect)) / mean_rgb(cropped(reference, k.rect));
    std::cout << "  " << k.name << " mean colour ratio " << ratio.r << " " << ratio.g << " " << ratio.b << "\n";
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ratio[c], 1.0, kMeanLimit) << k.name << " channel " << c;
  }
}

}  // namespace
}  // namespace kiln::test
