// LDR previews (renderer/film/tonemap.h) against values worked out here from the spec's formulas: the Photographic
// operator (log-average, key, burn percentile, gamma), the course LDR convention and clamp + gamma/sRGB; and the
// PNG that `kiln render` writes, read back and compared byte for byte with the preview of its own EXR.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"
#include "renderer/film/tonemap.h"

namespace kiln::test {
namespace {

int byte_of(double v01) { return int(std::lround(std::clamp(v01, 0.0, 1.0) * 255.0)); }

// 90 grey pixels of luminance 1 and 10 of luminance 100.
Image two_level_image() {
  Image img(10, 10);
  for (size_t i = 0; i < img.pixels().size(); ++i) img.pixels()[i] = Rgb(i < 90 ? 1.0f : 100.0f);
  return img;
}

PreviewSettings photographic(float key, float burn_percent, float gamma = 2.2f) {
  PreviewSettings p;
  p.kind = PreviewKind::Photographic;
  p.tonemap.key = key;
  p.tonemap.burn_percent = burn_percent;
  p.tonemap.gamma = gamma;
  return p;
}

// Reinhard 2002 as the spec writes it: L_avg = exp(mean log(delta + L)), scaled L = key L / L_avg, white point
// L_white = the scaled luminance at the (100 - burn)th percentile, Ld = L (1 + L / L_white^2) / (1 + L), gamma.
int expected_photographic(double lum, double key, double l_white_unscaled, double gamma) {
  const double delta = 1e-5;
  const double log_avg = std::exp(0.9 * std::log(delta + 1.0) + 0.1 * std::log(delta + 100.0));
  const double l = key * lum / log_avg, lw = key * l_white_unscaled / log_avg;
  const double ld = l * (1.0 + l / (lw * lw)) / (1.0 + l);
  return byte_of(std::pow(std::min(1.0, ld), 1.0 / gamma));
}

// Why: the log-average (not the arithmetic mean: 10.9 here, against a log-average of 1.58), the key and the burn
// percentile each move the dark pixels' byte; a 5% burn puts the white point on the bright pixels (they map to 255),
// a 50% burn on the dark ones (then they map to 255 too).
TEST(Tonemap, PhotographicFollowsLogAverageKeyAndBurnPercentile) {
  const Image img = two_level_image();
  struct Case {
    float key, burn;
    double white;  // unscaled luminance of the white point
  };
  for (const Case c : {Case{0.18f, 5.0f, 100.0}, Case{0.36f, 5.0f, 100.0}, Case{0.18f, 50.0f, 1.0}, Case{0.18f, 0.0f, 100.0}}) {
    const std::vector<uint8_t> ldr = to_ldr(img, photographic(c.key, c.burn));
    const int dark = expected_photographic(1.0, c.key, c.white, 2.2), bright = expected_photographic(100.0, c.key, c.white, 2.2);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_EQ(int(ldr[ch]), dark) << "key " << c.key << " burn " << c.burn;
      EXPECT_EQ(int(ldr[3 * 95 + size_t(ch)]), bright) << "key " << c.key << " burn " << c.burn;
    }
  }
  // The numbers the cases above rest on, worked by hand: key 0.18, burn 5% -> dark pixels at byte 90.
  EXPECT_EQ(int(to_ldr(img, photographic(0.18f, 5.0f))[0]), 90);
}

// Why: the course's LDR convention takes radiance already on the 0-255 scale (round, clamp, no gamma); clamp +
// gamma 2.2 and clamp + sRGB encode [0, 1].
TEST(Tonemap, CourseLdrAndClampGammaBytes) {
  Image img(4, 1);
  img.pixels() = {Rgb(0.0f), Rgb(12.4f), Rgb(127.6f), Rgb(300.0f)};
  PreviewSettings course;
  course.kind = PreviewKind::CourseLdr;
  const std::vector<uint8_t> c = to_ldr(img, course);
  EXPECT_EQ(std::vector<int>({c[0], c[3], c[6], c[9]}), std::vector<int>({0, 12, 128, 255}));

  Image unit(3, 1);
  unit.pixels() = {Rgb(0.5f), Rgb(0.002f), Rgb(2.0f)};
  PreviewSettings gamma;
  gamma.kind = PreviewKind::ClampGamma;
  gamma.srgb = false;
  gamma.gamma = 2.2f;
  const std::vector<uint8_t> g = to_ldr(unit, gamma);
  EXPECT_EQ(int(g[0]), byte_of(std::pow(0.5, 1 / 2.2)));  // 186
  EXPECT_EQ(int(g[3]), byte_of(std::pow(0.002, 1 / 2.2)));
  EXPECT_EQ(int(g[6]), 255);
  PreviewSettings srgb;
  srgb.kind = PreviewKind::ClampGamma;
  const std::vector<uint8_t> s = to_ldr(unit, srgb);
  EXPECT_EQ(int(s[0]), byte_of(1.055 * std::pow(0.5, 1 / 2.4) - 0.055));  // 188
  EXPECT_EQ(int(s[3]), byte_of(12.92 * 0.002));                            // the linear segment
  EXPECT_EQ(int(s[6]), 255);
}

// Why: the PNG `kiln render` writes is the camera's preview of the EXR it writes next to it (default.xml has a
// Photographic Tonemap), every byte.
TEST(Tonemap, RenderedPngIsThePreviewOfTheExr) {
  const std::string dir = tmp_dir("tonemap_png");
  const std::string scene_path = std::string(KILN_SOURCE_DIR) + "/scenes/default.xml";
  const std::string cmd = std::string(KILN_BINARY) + " render " + scene_path + " -o " + dir + " -q --spp 1 > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const SceneDesc scene = load_scene(scene_path);
  ASSERT_TRUE(scene.cameras[0].tonemap.has_value());
  const Image exr = read_exr(dir + "/default.exr").rgb;
  const std::vector<uint8_t> want = to_ldr(exr, preview_for_camera(scene.cameras[0], scene));
  const Image png = read_image(dir + "/default.png");
  ASSERT_EQ(png.width(), exr.width());
  ASSERT_EQ(png.height(), exr.height());
  size_t nonzero = 0;
  for (size_t i = 0; i < png.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const int got = int(std::lround(png.pixels()[i][c] * 255.0f));
      ASSERT_EQ(got, int(want[3 * i + size_t(c)])) << "pixel " << i << " channel " << c;
      nonzero += got > 0;
    }
  EXPECT_GT(nonzero, png.pixels().size());  // not a black image
}

}  // namespace
}  // namespace kiln::test
