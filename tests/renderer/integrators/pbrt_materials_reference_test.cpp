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

#include <cmath>
#include <fstream>
#include <sstream>

#include "renderer/analysis/image_compare.h"
#include "renderer/film/pixel_filter.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render_util.h"
#include "scenes/pbrt/loader.h"
#include "scenes/subdivision.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

constexpr uint32_t kSpp = 16;
constexpr int kBlock = 16;
constexpr double kMedianLimit = 0.02;
constexpr double kP95Limit = 0.08;
constexpr double kMeanLimit = 0.02;
// Regions of the 600x400 image (x0, y0, width, height), on the 16-px block grid: the three killeroos together and
// each one alone.
struct Region {
  const char* name;
  int r[4];
};
constexpr Region kKilleroos{"killeroos", {80, 112, 512, 144}};
constexpr Region kEachKilleroo[] = {{"mix killeroo", {80, 112, 112, 128}},
                                    {"diffusetransmission killeroo", {248, 112, 144, 128}},
                                    {"coatedconductor killeroo", {408, 112, 192, 128}}};

Rgb mean_rgb(const Image& img) {
  double s[3] = {0, 0, 0};
  for (const Rgb& p : img.pixels())
    for (int c = 0; c < 3; ++c) s[c] += p[c];
  const double n = double(img.pixels().size());
  return {float(s[0] / n), float(s[1] / n), float(s[2] / n)};
}

std::string features(const std::string& rel) { return shared_dir() + "/scenes/pbrt/features/" + rel; }

Image crop(const Image& img, const int (&r)[4]) {
  Image out(r[2], r[3]);
  for (int y = 0; y < r[3]; ++y)
    for (int x = 0; x < r[2]; ++x) out.at(x, y) = img.at(r[0] + x, r[1] + y);
  return out;
}

// The scene as Kiln reads it. While Kiln's loader skips pbrt's "disk" shape, the disk light is given as a 256-gon of
// the same radius (area within 1e-4 of the disk's), so that the comparison still sees the scene's main light.
SceneDesc load_materials_scene() {
  const std::string path = features("materials.pbrt");
  SceneDesc scene = load_scene(path);
  bool disk_skipped = false;
  for (const std::string& u : scene.unsupported) disk_skipped |= u.find("disk") != std::string::npos;
  if (!disk_skipped) return scene;
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  std::string s = text.str();
  const std::string disk = "Shape \"disk\" \"float radius\" [ 120 ]";
  const size_t at = s.find(disk);
  EXPECT_NE(at, std::string::npos);
  if (at == std::string::npos) return scene;
  constexpr int kSides = 256;
  std::ostringstream fan;
  fan << "Shape \"trianglemesh\" \"point3 P\" [ 0 0 0";
  for (int i = 0; i < kSides; ++i) {
    const double a = 2.0 * 3.14159265358979323846 * i / kSides;
    fan << ' ' << 120.0 * std::cos(a) << ' ' << 120.0 * std::sin(a) << " 0";
  }
  fan << " ] \"integer indices\" [";
  for (int i = 0; i < kSides; ++i) fan << ' ' << 0 << ' ' << 1 + i << ' ' << 1 + (i + 1) % kSides;
  fan << " ]";
  s.replace(at, disk.size(), fan.str());
  SceneDesc with_fan = parse_pbrt(s, path);
  apply_subdivision(with_fan);  // the killeroos' loopsubdiv, as load_scene does
  return with_fan;
}

void expect_within_limits(const BlockStats& st, const char* what) {
  std::cout << "materials.pbrt vs pbrt-v4, " << what << ", " << kSpp << " spp, " << kBlock << "-px blocks: median "
            << st.median_rel << ", p95 " << st.p95_rel << ", mean ratio " << st.mean_ratio << " over " << st.blocks
            << " blocks\n";
  EXPECT_EQ(st.left_out.image, 0u) << what << ": pixels that are not finite";
  EXPECT_LT(st.median_rel, kMedianLimit) << what;
  EXPECT_LT(st.p95_rel, kP95Limit) << what;
  EXPECT_NEAR(st.mean_ratio, 1.0, kMeanLimit) << what;
}

TEST(PbrtReference, MaterialsFeatureSceneMatchesPbrtV4) {
  KILN_NEED_SHARED_PATH(features("materials.pbrt"));
  const SceneDesc scene = load_materials_scene();
  const auto world = build_scene_world(scene);
  ASSERT_TRUE(world->features & kFeatureMix);
  const CameraDesc& cd = scene.cameras.at(0);
  const Camera cam(cd);
  Film film(cam.width(), cam.height());
  RenderOptions ro;
  ro.seed = 1;
  ro.spp_total = kSpp;
  ro.filter = pixel_filter_for(cd, std::nullopt);
  render_samples(*world, cam, scene_settings(cd, scene, world->features), ro, 0, kSpp, film);

  const Image reference = read_exr(features("reference/materials.exr")).rgb;
  const Image image = film.mean();
  ASSERT_EQ(image.width(), reference.width());
  ASSERT_EQ(image.height(), reference.height());
  expect_within_limits(block_luminance_stats(image, reference, kBlock), "whole image");
  expect_within_limits(block_luminance_stats(crop(image, kKilleroos.r), crop(reference, kKilleroos.r), kBlock),
                       kKilleroos.name);
  for (const Region& k : kEachKilleroo) {
    const Image a = crop(image, k.r), b = crop(reference, k.r);
    expect_within_limits(block_luminance_stats(a, b, kBlock), k.name);
    const Rgb ratio = mean_rgb(a) / mean_rgb(b);
    std::cout << "  " << k.name << " mean colour ratio " << ratio.r << " " << ratio.g << " " << ratio.b << "\n";
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ratio[c], 1.0, kMeanLimit) << k.name << " channel " << c;
  }
}

}  // namespace
}  // namespace kiln::test
