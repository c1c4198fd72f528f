// The CS171 render path end to end through `kiln render` on a tiny config: the config's radiance reaches the EXR
// unscaled (pixels inside the light hold exactly its radiance), max_depth is the spec's vertex count (max_depth 1:
// direct light only, so the ceiling, which faces away from the light, is black), and the PNG is pow(L, 1/2.2) of
// the EXR, byte for byte.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"

namespace kiln::test {
namespace {

constexpr int kRes = 32;
const Rgb kRadiance{17.0f, 12.0f, 5.0f};

std::string tiny_config(int max_depth) {
  const std::string assets = std::string(KILN_SOURCE_DIR) + "/scenes/cs171/assets/";
  std::string objects;
  for (const char* part : {"floor", "ceiling", "back", "left", "right"})
    objects += std::string(objects.empty() ? "" : ",") + R"({"obj_file_path": ")" + assets + part +
               R"(.obj", "material_name": "grey", "translate": [0,0,0], "scale": 1, "has_bvh": false})";
  return R"({"spp": 16, "max_depth": )" + std::to_string(max_depth) + R"(, "image_resolution": [32, 32],
  "cam_config": {"position": [0,1,2.5], "look_at": [0,1.98,0], "ref_up": [0,1,0], "vertical_fov": 19.5, "focal_length": 1},
  "light_config": {"position": [0,1.98,0], "size": [0.5,0.5], "radiance": [17.0,12.0,5.0]},
  "materials": [{"color": [0.725, 0.71, 0.68], "type": "diffuse", "name": "grey"}],
  "objects": [)" + objects + "]}";
}

TEST(Cs171Render, RadianceDepthAndGammaPreviewEndToEnd) {
  const std::string dir = tmp_dir("cs171_render");
  const std::string config = dir + "/tiny.json";
  std::ofstream(config) << tiny_config(1);
  const std::string cmd = std::string(KILN_BINARY) + " render " + config + " -o " + dir + "/out -q > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const ExrFile exr = read_exr(dir + "/out/tiny.exr");
  ASSERT_EQ(exr.rgb.width(), kRes);
  EXPECT_EQ(exr.find("kiln:rules"), "CS171 course rules");
  EXPECT_EQ(exr.find("kiln:integrator"), "Kiln path tracer: brdf+nee, max depth 1");
  EXPECT_EQ(exr.find("kiln:spp"), "16");

  // Radiance convention: every sample of a pixel inside the light's image sees its radiance, nothing else.
  size_t light_pixels = 0;
  for (const Rgb& p : exr.rgb.pixels())
    if (p.r == kRadiance.r && p.g == kRadiance.g && p.b == kRadiance.b) ++light_pixels;
  EXPECT_GE(light_pixels, 4u);
  float max_r = 0;
  for (const Rgb& p : exr.rgb.pixels()) max_r = std::max(max_r, p.r);
  EXPECT_EQ(max_r, kRadiance.r) << "nothing is brighter than the light at max_depth 1";

  // Depth: the camera looks up at the light from inside the box's opening; its top row sees only the ceiling
  // between the light and the opening: black at max_depth 1, lit at max_depth 2 (one bounce more).
  auto top_row = [](const Image& img) {
    double sum = 0;
    for (int x = 0; x < img.width(); ++x) sum += img.pixels()[size_t(x)].luminance();
    return sum;
  };
  EXPECT_EQ(top_row(exr.rgb), 0.0);
  std::ofstream(dir + "/tiny2.json") << tiny_config(2);
  const std::string cmd2 = std::string(KILN_BINARY) + " render " + dir + "/tiny2.json -o " + dir + "/out -q > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd2.c_str()), 0);
  EXPECT_GT(top_row(read_exr(dir + "/out/tiny2.exr").rgb), 0.0);

  // The preview: pow(clamp(L, 0, 1), 1/2.2), rounded to 8 bits.
  const Image png = read_image(dir + "/out/tiny.png");
  ASSERT_EQ(png.width(), kRes);
  for (size_t i = 0; i < png.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double l = std::clamp(double(exr.rgb.pixels()[i][c]), 0.0, 1.0);
      const long want = std::lround(std::pow(l, 1.0 / 2.2) * 255.0);
      ASSERT_NEAR(std::lround(png.pixels()[i][c] * 255.0f), want, 0) << "pixel " << i << " channel " << c;
    }
}

}  // namespace
}  // namespace kiln::test
