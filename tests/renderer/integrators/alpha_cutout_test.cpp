// Alpha cut-outs (pbrt "alpha") in the renderer. A Lambertian floor lit by a square light (off the point's axis,
// so that no symmetry hides a mistake in u or v) through an occluder in between receives exactly the light's open
// part: for an occluder of opacity a over the whole light, (1 - a) of the irradiance; for one right under the light
// whose image alpha is transparent on one half (nearest-texel lookups, so the boundary is sharp), the irradiance of
// the light's part behind that half, in closed form. NEE alone (shadow rays) and BSDF sampling alone (bounce rays)
// both pass through it; camera rays do too (a camera in the boundary's vertical plane, looking up through the
// occluder, sees the light on exactly half its view). A scene whose shapes are opaque builds no alpha test at all.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/image_io/image_io.h"
#include "renderer/test_scenes.h"

namespace kiln::test {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kAlbedo = 0.5f;
constexpr float kL = 3.0f;
constexpr float kLightHeight = 2.0f;
constexpr float kLightX = 0.3f, kLightZ = 0.15f;  // the unit light's centre: x in [-0.2, 0.8], z in [-0.35, 0.65]
// The occluder sits just under the light, centred where the line from the floor's origin to the light's centre
// crosses its plane: the middle of its image then splits the light, seen from the origin, exactly at its centre.
constexpr float kOccluderHeight = kLightHeight - 0.01f;
constexpr float kShrink = kOccluderHeight / kLightHeight;
constexpr double kMaxZ = 5.0;

// The irradiance at the origin from the part [x0, x1] x [z0, z1] of the light's plane: the corner rectangles from
// the point straight above the origin, signed, by inclusion and exclusion.
double rect_irradiance(double x0, double x1, double z0, double z1) {
  const auto g = [](double x, double z) {
    const double sign = (x < 0 ? -1.0 : 1.0) * (z < 0 ? -1.0 : 1.0);
    return sign * corner_rectangle_irradiance(kL, std::abs(x), std::abs(z), kLightHeight);
  };
  return g(x1, z1) - g(x0, z1) - g(x1, z0) + g(x0, z0);
}

// A horizontal square of side `size` centred at (x, y, z), its (v1-v0)x(v2-v0) facing down, uv over [0, 1]^2 along
// x and z.
MeshDesc square(const std::string& name, Vec3f c, float size, int material) {
  MeshDesc m;
  m.name = name;
  const float h = 0.5f * size;
  m.positions = {{c.x - h, c.y, c.z - h}, {c.x + h, c.y, c.z - h}, {c.x + h, c.y, c.z + h}, {c.x - h, c.y, c.z + h}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};  // (1,0,0) x (1,0,1) = (0,-1,0): down
  m.material = material;
  return m;
}

// Floor (material 0, albedo kAlbedo), the unit square light at kLightHeight facing down, a black occluder
// (material 1) of side `occluder_size` centred at `occluder`.
SceneDesc lit_floor(Vec3f occluder, float occluder_size) {
  SceneDesc s = lit_floor_scene(kAlbedo, "alpha.test");
  MaterialDesc black = s.materials[0];
  black.diffuse = Rgb(0.0f);
  s.materials.push_back(black);
  MeshDesc light = square("light", {kLightX, kLightHeight, kLightZ}, 1.0f, 0);
  light.emission = Rgb(kL);
  s.meshes.push_back(light);
  s.meshes.push_back(square("occluder", occluder, occluder_size, 1));
  return s;
}

// An 8 x 8 PNG, transparent (0) on half of it and opaque (255) on the other: the left columns (`columns`), else the
// top rows.
std::string half_open_png(bool columns) {
  const std::string path = tmp_dir("alpha_cutout") + (columns ? "/left_open.png" : "/top_open.png");
  constexpr int kW = 8;
  std::vector<uint8_t> rgb(3 * kW * kW);
  for (int y = 0; y < kW; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) rgb[size_t(3 * (y * kW + x) + c)] = (columns ? x : y) < kW / 2 ? 0 : 255;
  write_png(path, rgb, kW, kW);
  return path;
}

// The occluder just under the light, its alpha the float texture t.
SceneDesc occluder_with_alpha(const PbrtTextureDesc& t) {
  SceneDesc s = lit_floor({kLightX * kShrink, kOccluderHeight, kLightZ * kShrink}, 1.01f);
  s.pbrt_textures.push_back(t);
  s.meshes[2].alpha.texture = 0;
  return s;
}

// Its alpha an image half open; nearest-texel lookups keep the boundary sharp.
SceneDesc half_open_occluder(bool columns) {
  PbrtTextureDesc t;
  t.name = "half-open alpha";
  t.cls = TextureClass::ImageMap;
  t.is_float = true;
  t.image.path = half_open_png(columns);
  t.image.filter = ImageFilter::Point;
  return occluder_with_alpha(t);
}

void expect_floor_radiance(const SceneDesc& s, double irradiance, const char* what) {
  const auto w = build_world(s, {});
  ASSERT_TRUE(w->features & kFeatureAlpha);
  expect_floor_radiance_under_strategies(*w, s.cameras[0], kAlbedo / kPiD * irradiance, 60000, kMaxZ, what);
}

constexpr double kX0 = kLightX - 0.5, kX1 = kLightX + 0.5, kZ0 = kLightZ - 0.5, kZ1 = kLightZ + 0.5;

TEST(AlphaCutout, AnOccluderOfOpacityAPassesOneMinusAOfTheLight) {
  // At half height it covers the light (seen from the origin: the light's extent halved) and stays clear of the
  // camera's ray.
  SceneDesc s = lit_floor({0.5f * kLightX, 1.0f, 0.5f * kLightZ}, 1.0f);
  s.meshes[2].alpha.value = 0.35f;
  expect_floor_radiance(s, 0.65 * rect_irradiance(kX0, kX1, kZ0, kZ1), "opacity 0.35");
}

TEST(AlphaCutout, AHalfOpenImageLetsExactlyTheLightBehindItsOpenHalfThrough) {
  // The occluder (1.01x the light's size) covers all of the light but the part behind its open half: the light's
  // x < kLightX half for an image open on its left (u < 1/2), its z > kLightZ half for one open on its top rows
  // (pbrt reads images with t = 1 - v: the top rows are v > 1/2).
  expect_floor_radiance(half_open_occluder(true), rect_irradiance(kX0, kLightX, kZ0, kZ1), "left half open");
  expect_floor_radiance(half_open_occluder(false), rect_irradiance(kX0, kX1, kLightZ, kZ1), "top half open");
}

// The same occluders with a procedural alpha: a 2-D checkerboard two cells across u (or v), open (0) on the cell that
// the image leaves open and opaque (1) on the other. Alpha reads any float texture of the scene's texture graph.
SceneDesc half_open_checker_occluder(bool columns) {
  PbrtTextureDesc t;
  t.name = "half-open checkerboard";
  t.cls = TextureClass::Checkerboard;
  t.is_float = true;
  (columns ? t.mapping.su : t.mapping.sv) = 2.0f;  // cell 0 below 1/2, cell 1 above
  t.operands[kTexOperandTex1] = Rgb(columns ? 0.0f : 1.0f);
  t.operands[kTexOperandTex2] = Rgb(columns ? 1.0f : 0.0f);
  return occluder_with_alpha(t);
}

TEST(AlphaCutout, AProceduralTextureCutsAsTheImageDoes) {
  expect_floor_radiance(half_open_checker_occluder(true), rect_irradiance(kX0, kLightX, kZ0, kZ1), "left half open");
  expect_floor_radiance(half_open_checker_occluder(false), rect_irradiance(kX0, kX1, kLightZ, kZ1), "top half open");
}

TEST(AlphaCutout, CameraRaysSeeTheLightThroughTheOpenHalf) {
  // From under the occluder, in the vertical plane of its image's boundary, looking straight up at the light: half
  // the view sees the light (kL), the other half the black occluder.
  for (const bool columns : {true, false}) {
    SceneDesc s = half_open_occluder(columns);
    CameraDesc& cam = s.cameras[0];
    cam.position = columns ? Vec3f(kLightX * kShrink, 0.5f, 0.1f) : Vec3f(0.2f, 0.5f, kLightZ * kShrink);
    cam.gaze = {0, 1, 0};
    cam.up = {0, 0, 1};
    cam.fov_y_deg = 10.0f;
    const auto w = build_world(s, {});
    PathSettings p;
    p.max_depth = 0;
    const Estimate e = estimate_mean(*w, p, cam, 40000);
    EXPECT_NEAR(e.mean, 0.5 * kL, kMaxZ * e.stderr_) << (columns ? "left" : "top") << ": " << e.mean << " +- "
                                                     << e.stderr_;
  }
}

TEST(AlphaCutout, OpaqueShapesBuildNoAlphaTest) {
  SceneDesc s = lit_floor({0.5f * kLightX, 1.0f, 0.5f * kLightZ}, 1.0f);
  s.meshes[2].alpha.value = 1.0f;  // pbrt's default: no cut-out
  const auto w = build_world(s, {});
  EXPECT_FALSE(w->features & kFeatureAlpha);
  EXPECT_FALSE(w->alpha);
  EXPECT_EQ(w->geometry.alpha.opacity, nullptr);
  for (const Shape& shape : w->geometry.shapes) EXPECT_FALSE(shape.alpha);
}

}  // namespace
}  // namespace kiln::test
