// Filtered image textures (`Interpolation` trilinear / ewa) and the footprint they are filtered over
// (renderer/texture/footprint.h): MIP averages of images whose averages are known, and the footprint of a plane seen
// by a pinhole camera against its closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/render_util.h"
#include "renderer/world/camera.h"
#include "renderer/image_io/image_io.h"
#include "renderer/world/hit_textures.h"
#include "renderer/world/interaction.h"
#include "renderer/texture/footprint.h"
#include "renderer/texture/scene_textures.h"
#include "renderer/world/world.h"

namespace kiln::test {
namespace {

constexpr int kSize = 64;  // texels per side of the test images (a power of two: every MIP level is exact)

template <typename F>
std::string write_grey_exr(const std::string& name, F f) {
  Image img(kSize, kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) img.at(x, y) = Rgb(f(x, y));
  const std::string path = tmp_dir("texture_filter") + "/" + name;
  write_exr(path, img, {}, {});
  return path;
}

SceneDesc scene_with_image(const std::string& path, TextureFilter filter) {
  SceneDesc s;
  s.source_path = "test.xml";
  TextureDesc t;
  t.name = "Texture id=1";
  t.source = TextureSource::Image;
  t.image_path = path;
  t.filter = filter;
  s.textures.push_back(std::move(t));
  return s;
}

float grey(const SceneTextures& tex, Vec2f uv, const UvFootprint& fp) { return tex.value(0, uv, {}, fp).r; }

Vec2f texel_centre(int x, int y) { return {(float(x) + 0.5f) / kSize, (float(y) + 0.5f) / kSize}; }

UvFootprint isotropic(float texels_per_pixel) {
  const float d = texels_per_pixel / kSize;
  return {d, 0.0f, 0.0f, d};
}

// A one-texel checkerboard of 0 and 1: every 2x2 block, so every MIP level above the finest, averages 1/2.
float checker(int x, int y) { return float((x + y) % 2); }

// Seen from far away (16 texels per pixel) the checkerboard is its average: the filtered lookups return 1/2, where
// bilinear still returns the one texel under the point (aliasing).
TEST(TextureFilter, LargeFootprintGivesTheMipAverage) {
  const std::string path = write_grey_exr("checker.exr", checker);
  const SceneTextures bilinear(scene_with_image(path, TextureFilter::Bilinear), {});
  const SceneTextures trilinear(scene_with_image(path, TextureFilter::Trilinear), {});
  const SceneTextures ewa(scene_with_image(path, TextureFilter::Ewa), {});
  const UvFootprint far = isotropic(16.0f);
  for (const auto& [x, y] : {std::pair{5, 7}, std::pair{6, 7}, std::pair{31, 40}}) {
    const Vec2f uv = texel_centre(x, y);
    EXPECT_EQ(grey(bilinear, uv, far), checker(x, y)) << x << "," << y;
    EXPECT_NEAR(grey(trilinear, uv, far), 0.5f, 1e-3f) << x << "," << y;
    EXPECT_NEAR(grey(ewa, uv, far), 0.5f, 1e-3f) << x << "," << y;
  }
}

// A footprint far below a texel reads the finest level: the filtered lookups equal bilinear interpolation.
TEST(TextureFilter, TinyFootprintEqualsBilinear) {
  const std::string path =
      write_grey_exr("ramp.exr", [](int x, int y) { return 0.01f * float(x) + 0.003f * float(y * y % 17); });
  const SceneTextures bilinear(scene_with_image(path, TextureFilter::Bilinear), {});
  const SceneTextures trilinear(scene_with_image(path, TextureFilter::Trilinear), {});
  const SceneTextures ewa(scene_with_image(path, TextureFilter::Ewa), {});
  const UvFootprint near = isotropic(1e-3f);
  for (const Vec2f uv : {Vec2f(0.3137f, 0.7071f), Vec2f(0.5f, 0.25f), Vec2f(0.123f, 0.456f)}) {
    const float b = grey(bilinear, uv, {});
    EXPECT_NEAR(grey(trilinear, uv, near), b, 1e-5f) << uv.x << "," << uv.y;
    EXPECT_NEAR(grey(ewa, uv, near), b, 1e-5f) << uv.x << "," << uv.y;
  }
}

// Horizontal stripes 8 rows tall, seen with a footprint 32 texels long along s and far below a texel along t (a
// grazing view along the stripes): ewa averages along s only, where the image is constant, and keeps the stripe's
// value; trilinear blurs both axes by the longer one, over four stripes, to their average 1/2.
TEST(TextureFilter, EwaFiltersAlongTheFootprintOnly) {
  const auto stripes = [](int, int y) { return float((y / 8) % 2 == 0); };
  const std::string path = write_grey_exr("stripes.exr", stripes);
  const SceneTextures trilinear(scene_with_image(path, TextureFilter::Trilinear), {});
  const SceneTextures ewa(scene_with_image(path, TextureFilter::Ewa), {});
  const UvFootprint along_s{32.0f / kSize, 0.0f, 0.0f, 1e-4f};
  for (const int y : {3, 4, 11, 12}) {
    const Vec2f uv = texel_centre(20, y);
    EXPECT_NEAR(grey(ewa, uv, along_s), stripes(0, y), 0.02f) << y;
    EXPECT_NEAR(grey(trilinear, uv, along_s), 0.5f, 0.02f) << y;
  }
}

// ---- the footprint ----------------------------------------------------------------------------------------------

constexpr float kFovYDeg = 40.0f;
constexpr int kWidth = 320, kHeight = 200;

Camera pinhole() {
  CameraDesc d;
  d.use_fov = true;
  d.fov_y_deg = kFovYDeg;
  d.width = kWidth;
  d.height = kHeight;
  d.near_distance = 0.5f;  // not 1: the spread is per unit distance, whatever the image plane's
  d.position = Vec3f(0.5f, -1.0f, 2.0f);
  d.gaze = Vec3f(0, 0, -1);
  d.up = Vec3f(0, 1, 0);
  return Camera(d);
}

// One pixel of a pinhole camera with vertical field of view f and H rows covers 2 d tan(f/2) / H of a plane facing
// it at distance d (square pixels: the same along x).
float pixel_size_at(float d) { return 2.0f * d * std::tan(radians(kFovYDeg) * 0.5f) / float(kHeight); }

TEST(TextureFootprint, FrontoParallelPlaneCoversOnePixelPerStep) {
  const Camera cam = pinhole();
  const CameraSpread spread = cam.pixel_spread();
  const Vec3f n(0, 0, 1);
  for (const float d : {1.0f, 7.5f, 40.0f}) {
    const Vec3f p = spread.origin + Vec3f(0, 0, -d);  // on the axis
    Vec3f dpdx, dpdy;
    approximate_dp_dxy(spread, p, n, dpdx, dpdy);
    const float expected = pixel_size_at(d);
    EXPECT_NEAR(dpdx.x, expected, 1e-3f * expected) << d;  // film x is the camera's right, +x
    EXPECT_NEAR(dpdy.y, -expected, 1e-3f * expected) << d;  // film y runs down the image, -y
    EXPECT_NEAR(length(dpdx), expected, 1e-3f * expected) << d;
    EXPECT_NEAR(length(dpdy), expected, 1e-3f * expected) << d;
  }
  // Off the axis the approximation (the spread turned to look at the point) grows by 1 / cos^2 of the angle: half
  // way up the image (10.3 degrees) that is 3.3%; within 4% of the true, constant pixel size.
  const float d = 5.0f;
  const Vec3f p = spread.origin + Vec3f(0, 0.5f * d * std::tan(radians(kFovYDeg) * 0.5f), -d);
  Vec3f dpdx, dpdy;
  approximate_dp_dxy(spread, p, n, dpdx, dpdy);
  EXPECT_NEAR(length(dpdx), pixel_size_at(d), 0.04f * pixel_size_at(d));
  EXPECT_NEAR(length(dpdy), pixel_size_at(d), 0.04f * pixel_size_at(d));
}

// The texture footprint of a hit on that plane: u along x at 3 units per texture period, v down at 2, so one pixel
// step changes u by pixel / 3 along x only and v by pixel / 2 along y only.
TEST(TextureFootprint, HitFootprintInTextureCoordinates) {
  const Camera cam = pinhole();
  const float d = 12.0f;
  SurfaceInteraction si;
  si.p = cam.pixel_spread().origin + Vec3f(0, 0, -d);
  si.ng = si.ns = Vec3f(0, 0, 1);
  si.dpdu = Vec3f(3, 0, 0);
  si.dpdv = Vec3f(0, -2, 0);
  const UvFootprint fp = hit_footprint(cam.pixel_spread(), si);
  const float px = pixel_size_at(d);
  EXPECT_NEAR(fp.dudx, px / 3.0f, 1e-3f * px / 3.0f);
  EXPECT_NEAR(fp.dvdy, px / 2.0f, 1e-3f * px / 2.0f);
  EXPECT_NEAR(fp.dvdx, 0.0f, 1e-6f);
  EXPECT_NEAR(fp.dudy, 0.0f, 1e-6f);
}

// Least squares on skewed dp/du, dp/dv (not orthogonal, not unit): the (du, dv) found rebuild dp/dx and dp/dy
// exactly when they lie in the surface's plane, and give the projection's coefficients when they do not.
TEST(TextureFootprint, UvFootprintSolvesForSkewedDerivatives) {
  const Vec3f dpdu(2, 1, 0), dpdv(-0.5f, 1.5f, 0);
  const Vec3f dpdx = dpdu * 0.3f + dpdv * -0.7f, dpdy = dpdu * -0.2f + dpdv * 0.9f;
  const UvFootprint fp = uv_footprint(dpdx + Vec3f(0, 0, 0.4f), dpdy, dpdu, dpdv);  // x's normal part is dropped
  EXPECT_NEAR(fp.dudx, 0.3f, 1e-5f);
  EXPECT_NEAR(fp.dvdx, -0.7f, 1e-5f);
  EXPECT_NEAR(fp.dudy, -0.2f, 1e-5f);
  EXPECT_NEAR(fp.dvdy, 0.9f, 1e-5f);
  // Parallel derivatives have no solution: no footprint rather than NaN.
  const UvFootprint none = uv_footprint(dpdx, dpdy, dpdu, dpdu * 2.0f);
  EXPECT_EQ(none.dudx, 0.0f);
  EXPECT_EQ(none.dvdy, 0.0f);
}

// ---- through a render ------------------------------------------------------------------------------------------

// The checkerboard on a quad that fills a 16 x 16 pinhole view, 16 texels per pixel, as replace_all (the texel is
// the pixel's value, unshaded: no noise). Filtered, every pixel is the board's average, even at 1 spp; bilinear
// shows the texel under each sample, 0 or 1 or between. Through render_samples: the camera reaches the textures.
SceneDesc checker_wall(const std::string& path, TextureFilter filter) {
  SceneDesc s = lambertian_scene(0.5f, "test.xml");
  TextureDesc t;
  t.name = "Texture id=1";
  t.source = TextureSource::Image;
  t.image_path = path;
  t.filter = filter;
  t.decal = DecalMode::ReplaceAll;
  s.textures.push_back(t);
  CameraDesc c;
  c.use_fov = true;
  c.fov_y_deg = kFovYDeg;
  c.width = c.height = 16;
  c.renderer = RendererKind::PathTracing;
  s.cameras.push_back(c);
  const float d = 3.0f, h = d * std::tan(radians(kFovYDeg) * 0.5f);
  const float periods = 4.0f;  // 4 x 64 texels across 16 pixels
  MeshDesc m;
  m.name = "Mesh id=1";
  m.positions = {{-h, -h, -d}, {h, -h, -d}, {h, h, -d}, {-h, h, -d}};
  m.uvs = {{0, periods}, {periods, periods}, {periods, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = 0;
  m.textures = {0};
  s.meshes.push_back(m);
  return s;
}

float largest_deviation_from_half(const Image& img) {
  float worst = 0.0f;
  for (const Rgb& p : img.pixels()) worst = std::max(worst, std::fabs(p.r - 0.5f));
  return worst;
}

TEST(TextureFilter, RenderedWallOfCheckersIsItsAverage) {
  const std::string path = write_grey_exr("checker_wall.exr", checker);
  for (const TextureFilter f : {TextureFilter::Trilinear, TextureFilter::Ewa, TextureFilter::Bilinear}) {
    const SceneDesc s = checker_wall(path, f);
    const auto w = build_scene_world(s);
    const bool filtered = f != TextureFilter::Bilinear;
    EXPECT_EQ(w->textures->stats().filtered, filtered ? 1u : 0u);
    EXPECT_EQ(w->textures->stats().footprint_bindings, filtered ? 1u : 0u);
    const Image img = render_image(*w, s.cameras[0], scene_settings(s.cameras[0], s, w->features), 1);
    const float worst = largest_deviation_from_half(img);
    if (f == TextureFilter::Bilinear)
      EXPECT_GT(worst, 0.25f);  // aliasing: some sample lands near a texel's centre
    else
      EXPECT_LT(worst, 0.01f) << int(f);
  }
}

}  // namespace
}  // namespace kiln::test
