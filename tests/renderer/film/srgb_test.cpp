// The sRGB transfer curve of the PNG preview (IEC 61966-2-1, not a 2.2 power) at known points, and the 2018
// GammaCorrection sRGB spelling without a Tonemap: the course's 0-255 value goes through the curve.
#include <gtest/gtest.h>

#include "renderer/film/tonemap.h"

namespace kiln {
namespace {

TEST(Srgb, TransferCurveAtKnownPoints) {
  EXPECT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgb_encode(1.0f), 1.0f);
  EXPECT_NEAR(srgb_encode(0.0031308f), 0.040449936f, 1e-6f);  // where the linear segment meets the power segment
  EXPECT_NEAR(srgb_encode(0.001f), 0.01292f, 1e-7f);          // linear segment: 12.92 x
  EXPECT_NEAR(srgb_encode(0.5f), 0.735356983f, 1e-6f);
  EXPECT_NEAR(srgb_encode(0.18f), 0.461356f, 1e-5f);
  EXPECT_GT(std::abs(srgb_encode(0.5f) - std::pow(0.5f, 1.0f / 2.2f)), 0.005f) << "not the 2.2 power";
}

TEST(Srgb, GammaCorrectionWithoutTonemapEncodesTheCourseLdrValue) {
  SceneDesc scene;
  CameraDesc cam;
  cam.image_name = "out.png";
  cam.srgb_without_tonemap = true;
  const PreviewSettings p = preview_for_camera(cam, scene);
  EXPECT_EQ(p.kind, PreviewKind::CourseLdr);
  EXPECT_TRUE(p.course_ldr_srgb);
  Image img(3, 1);
  img.at(0, 0) = Rgb(0.5f * 255.0f);
  img.at(1, 0) = Rgb(0.0f);
  img.at(2, 0) = Rgb(1000.0f);
  const std::vector<uint8_t> ldr = to_ldr(img, p);
  EXPECT_EQ(ldr[0], 188);  // round(0.7354 * 255)
  EXPECT_EQ(ldr[3], 0);
  EXPECT_EQ(ldr[6], 255);
  cam.srgb_without_tonemap = false;
  EXPECT_EQ(to_ldr(img, preview_for_camera(cam, scene))[0], 128) << "the plain course LDR value";
}

}  // namespace
}  // namespace kiln
