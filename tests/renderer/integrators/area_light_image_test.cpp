// pbrt-v4 area lights that emit an image (AreaLightSource "diffuse" "string filename"): camera rays see the image's
// texels at the surface's (u, v) (v up, pbrt's flip of the image rows), and the same radiance reaches a Lambertian
// floor through light samples (NEE), BSDF-sampled rays and MIS: a constant image c lights it as "L" c does (the
// closed form of a rectangle's irradiance), an image whose right half is black as the left half rectangle alone.
// Bad input: a missing image, "filename" with "L".
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "renderer/test_scenes.h"

namespace kiln::test {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr double kMaxZ = 5.0;

std::string write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

// An image whose four quadrants are a (top left), b (top right), c (bottom left), d (bottom right).
Image quadrants(int n, Rgb a, Rgb b, Rgb c, Rgb d) {
  Image img(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) img.at(x, y) = y < n / 2 ? (x < n / 2 ? a : b) : (x < n / 2 ? c : d);
  return img;
}

// The quad [-1, 1]^2 at z = 0, (u, v) = ((x + 1) / 2, (y + 1) / 2), emitting image.exr x 2 towards a camera at
// z = -5 that looks at it along +z (x to the right of the frame, y up) with a 20 degree field of view.
constexpr float kScale = 2.0f;
constexpr int kRes = 16;
constexpr float kHalfView = 0.8816349f;  // 5 tan(10 degrees): the half width of the quad the frame shows
const char* kQuadScene = R"(LookAt 0 0 -5  0 0 0  0 1 0
Camera "perspective" "float fov" 20
Film "rgb" "integer xresolution" 16 "integer yresolution" 16 "string filename" "quad.exr"
PixelFilter "box"
Sampler "independent" "integer pixelsamples" 4
WorldBegin
AttributeBegin
  AreaLightSource "diffuse" "string filename" "image.exr" "float scale" 2 "bool twosided" true
  Shape "trianglemesh" "point3 P" [-1 -1 0  1 -1 0  1 1 0  -1 1 0] "point2 uv" [0 0  1 0  1 1  0 1]
    "integer indices" [0 1 2  0 2 3]
AttributeEnd
)";

// The same quad as one bilinear patch without "uv": pbrt's patch (u, v), (0,0) at P[0] ... (1,1) at P[3].
std::string as_bilinear_patch(std::string scene) {
  const size_t from = scene.find("  Shape"), to = scene.find("AttributeEnd");
  return scene.replace(from, to - from, "  Shape \"bilinearmesh\" \"point3 P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n");
}

class AreaLightImageShapes : public ::testing::TestWithParam<bool> {};

TEST_P(AreaLightImageShapes, CameraRaysSeeTheTexelsAtTheSurfacesUv) {
  const bool patch = GetParam();
  const std::string dir = tmp_dir(patch ? "area_light_image/camera_patch" : "area_light_image/camera");
  const Rgb a(1, 0, 0), b(0, 1, 0), c(0, 0, 1), d(1, 1, 0.5f);
  write_exr(dir + "/image.exr", quadrants(8, a, b, c, d), {}, {});
  const SceneDesc s =
      load_scene(write_text(dir + "/quad.pbrt", patch ? as_bilinear_patch(kQuadScene) : std::string(kQuadScene)));
  ASSERT_EQ(s.external_files.size(), 1u);
  EXPECT_EQ(std::filesystem::path(s.external_files[0]).filename(), "image.exr");
  const auto w = build_scene_world(s);
  ASSERT_EQ(w->stats.mesh_lights, 1u);
  const Image img = render_like_kiln(s, *w, 4, 1);
  ASSERT_EQ(img.width(), kRes);
  // A pixel away from the quadrants' borders (in u and v: half a texel of bilinear blending, half a pixel's
  // footprint) sees its quadrant's texel exactly.
  const float texel = 1.0f / 8.0f, footprint = kHalfView / kRes;
  int checked = 0;
  for (int py = 0; py < kRes; ++py)
    for (int px = 0; px < kRes; ++px) {
      const float x = ((float(px) + 0.5f) / kRes * 2.0f - 1.0f) * kHalfView;
      const float y = (1.0f - (float(py) + 0.5f) / kRes * 2.0f) * kHalfView;
      const float u = 0.5f * (x + 1.0f), v = 0.5f * (y + 1.0f);
      const float margin = 0.5f * texel + footprint;
      if (std::abs(u - 0.5f) < margin || std::abs(v - 0.5f) < margin) continue;
      const Rgb want = (v > 0.5f ? (u < 0.5f ? a : b) : (u < 0.5f ? c : d)) * kScale;
      const Rgb got = img.at(px, py);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(got[k], want[k], 1e-5f) << "pixel (" << px << ", " << py << ") channel " << k;
      ++checked;
    }
  EXPECT_GE(checked, 100);
}

INSTANTIATE_TEST_SUITE_P(AreaLightImage, AreaLightImageShapes, ::testing::Values(false, true),
                         [](const auto& param_info) { return param_info.param ? "BilinearPatch" : "TriangleMesh"; });

// A rectangle a x b at height h facing down, its corner above the origin of lit_floor_scene's floor, on the side away
// from its camera (z < 0, out of the camera's rays); u along x (a), v along -z (b). Emits `emission` x its image
// when given (image_path), else `emission`.
constexpr float kA = 1.0f, kB = 0.8f, kH = 0.7f, kAlbedo = 0.5f;
const Rgb kC(1.5f);

MeshDesc rectangle_light(Rgb emission, const std::string& image_path) {
  MeshDesc m;
  m.name = "rectangle light";
  m.positions = {{0, kH, 0}, {kA, kH, 0}, {kA, kH, -kB}, {0, kH, -kB}};
  m.indices = {0, 2, 1, 0, 3, 2};  // (v1-v0)x(v2-v0) = -y
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.emission = emission;
  if (!image_path.empty()) m.emission_image = EmissionImageDesc{image_path, "line 1 (test)"};
  return m;
}

// The floor's radiance at the origin under each strategy against albedo / pi x E.
void expect_floor_radiance(const MeshDesc& light, double irradiance, const std::string& what) {
  SceneDesc s = lit_floor_scene(kAlbedo, "test.pbrt");
  s.meshes.push_back(light);
  const auto w = build_world(s, {});
  ASSERT_EQ(w->stats.mesh_lights, 1u);
  expect_floor_radiance_under_strategies(*w, s.cameras[0], kAlbedo / kPiD * irradiance, 40000, kMaxZ, what);
}

TEST(AreaLightImage, ConstantImageLightsAFloorAsItsValueDoes) {
  const std::string dir = tmp_dir("area_light_image/constant");
  Image img(16, 16);
  for (Rgb& p : img.pixels()) p = kC;
  write_exr(dir + "/constant.exr", img, {}, {});
  const double e = corner_rectangle_irradiance(kC.r, kA, kB, kH);
  expect_floor_radiance(rectangle_light(kC, ""), e, "L = c");
  expect_floor_radiance(rectangle_light(Rgb(1.0f), dir + "/constant.exr"), e, "image c");
  expect_floor_radiance(rectangle_light(Rgb(2.0f), dir + "/constant.exr"), 2.0 * e, "image c, scale 2");
}

TEST(AreaLightImage, HalfBlackImageLightsAFloorAsTheLitHalfAlone) {
  const std::string dir = tmp_dir("area_light_image/half");
  constexpr int kN = 256;  // the bilinear ramp across u = 1/2 (one texel, symmetric) changes E by < 1e-4
  Image img(kN, kN);
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) img.at(x, y) = x < kN / 2 ? kC : Rgb(0.0f);
  write_exr(dir + "/half.exr", img, {}, {});
  expect_floor_radiance(rectangle_light(Rgb(1.0f), dir + "/half.exr"),
                        corner_rectangle_irradiance(kC.r, 0.5 * kA, kB, kH), "left half lit");
}

// A disk of radius 0.8 at height 1.5 above the origin, facing down; pbrt's (u, v) = (phi / 2 pi, (r_max - r) / r_max).
// Lit for u < 1/2 and v > 1/2 only (the image's top left quarter), it gives the origin (on its axis) half the
// irradiance pi L r^2 / (h^2 + r^2) of the inner disk of radius 0.4.
TEST(AreaLightImage, ImageOnADiskLightsTheFloorAsItsLitSectorAlone) {
  const std::string dir = tmp_dir("area_light_image/disk");
  constexpr int kN = 256;
  write_exr(dir + "/quarter.exr", quadrants(kN, kC, Rgb(0.0f), Rgb(0.0f), Rgb(0.0f)), {}, {});
  constexpr float kR = 0.8f, kDiskH = 1.5f;
  QuadricDesc q;
  q.name = "disk light";
  q.quadric = *make_quadric(QuadricType::Disk, kR, 0, 0, 0, 0, 360).quadric;
  q.to_world = Transform::translate({0, kDiskH, 0}) * Transform::rotate(90.0f, {1, 0, 0});  // object +z: world -y
  q.emission = Rgb(1.0f);
  q.emission_image = EmissionImageDesc{dir + "/quarter.exr", "line 1 (test)"};
  SceneDesc s = lit_floor_scene(kAlbedo, "test.pbrt");
  s.quadrics.push_back(q);
  const auto w = build_world(s, {});
  ASSERT_EQ(w->stats.quadric_lights, 1u);
  constexpr double kLitR = 0.5 * kR;
  const double e = 0.5 * kPiD * kC.r * kLitR * kLitR / (kDiskH * kDiskH + kLitR * kLitR);
  expect_floor_radiance_under_strategies(*w, s.cameras[0], kAlbedo / kPiD * e, 40000, kMaxZ, "lit quarter");
}

// `kiln render` of scene text `text` (written as NAME.pbrt) exits 2, names the scene file and each of `expected`,
// and writes nothing.
void expect_bad_input(const std::string& dir, const std::string& name, const std::string& text,
                      const std::vector<std::string>& expected) {
  std::filesystem::remove_all(dir + "/out");
  const auto [code, out] =
      run_kiln_command("render " + write_text(dir + "/" + name + ".pbrt", text) + " -q --spp 1 -o " + dir + "/out");
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find(name + ".pbrt"), std::string::npos) << out;
  for (const std::string& e : expected) EXPECT_NE(out.find(e), std::string::npos) << "no " << e << " in: " << out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out")) << name;
}

// The quad scene with its image file named `file` instead.
std::string with_image(const std::string& file) {
  std::string text = kQuadScene;
  return text.replace(text.find("image.exr"), 9, file);
}

TEST(AreaLightImage, BadInputExitsWithTheFileAndLineAndWritesNothing) {
  const std::string dir = tmp_dir("area_light_image/bad");
  expect_bad_input(dir, "missing", with_image("nothere.exr"), {"nothere.exr", "8"});  // the AreaLightSource's line
  std::string both = kQuadScene;
  both.replace(both.find("\"float scale\""), 0, "\"rgb L\" [1 1 1] ");
  expect_bad_input(dir, "both", both, {"line 8", "\"L\" and \"filename\""});
  write_text(dir + "/broken.exr", "not an image");
  expect_bad_input(dir, "broken", with_image("broken.exr"), {"broken.exr", "line 8"});
}

}  // namespace
}  // namespace kiln::test
