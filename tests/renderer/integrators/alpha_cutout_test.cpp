// Alpha cut-outs (pbrt "alpha") in the renderer. A Lambertian floor lit by a square light through an occluder in
// between receives exactly the light's open part: for an occluder of opacity a over the whole light, (1 - a) of
// the irradiance; for one right under the light whose image alpha is transparent on one half (nearest-texel lookups,
// so the boundary is sharp), the irradiance of the other half of the light, in closed form. NEE alone (shadow rays)
// and BSDF sampling alone (bounce rays) both pass through it; camera rays do too (a camera looking up through the
// half-open occluder sees half the light's radiance). A scene whose shapes are opaque builds no alpha test at all.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/image_io/image_io.h"
#include "renderer/render_util.h"

namespace kiln::test {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kAlbedo = 0.5f;
constexpr float kL = 3.0f;
constexpr float kLightHeight = 2.0f;
constexpr double kMaxZ = 5.0;

// Irradiance at a point from a parallel rectangle a x b at height h with its corner straight above the point (Howell
// C-11, times pi L).
double corner_rectangle_irradiance(double a, double b, double h) {
  const double x = a / h, y = b / h;
  const double f = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                    y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                   (2 * kPiD);
  return kPiD * kL * f;
}

// A horizontal square [-0.5, 0.5]^2 at height y, its (v1-v0)x(v2-v0) facing down, uv over [0, 1]^2 along x and z.
MeshDesc square(const std::string& name, float y, int material) {
  MeshDesc m;
  m.name = name;
  m.positions = {{-0.5f, y, -0.5f}, {0.5f, y, -0.5f}, {0.5f, y, 0.5f}, {-0.5f, y, 0.5f}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};  // (1,0,0) x (1,0,1) = (0,-1,0): down
  m.material = material;
  return m;
}

// Floor (material 0, albedo kAlbedo), a square light at kLightHeight facing down, a black occluder (material 1).
SceneDesc lit_floor(float occluder_height, float occluder_scale) {
  SceneDesc s = lambertian_scene(kAlbedo, "alpha.test");
  MaterialDesc black = s.materials[0];
  black.diffuse = Rgb(0.0f);
  s.materials.push_back(black);
  MeshDesc floor;
  floor.name = "floor";
  floor.positions = {{-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  floor.material = 0;
  s.meshes.push_back(floor);
  MeshDesc light = square("light", kLightHeight, 0);
  light.emission = Rgb(kL);
  s.meshes.push_back(light);
  MeshDesc occluder = square("occluder", occluder_height, 1);
  for (Vec3f& p : occluder.positions) p = Vec3f(p.x * occluder_scale, p.y, p.z * occluder_scale);
  s.meshes.push_back(occluder);
  CameraDesc cam;
  cam.position = {0.0f, 3.0f, 3.0f};
  cam.gaze = normalize(Vec3f{0.0f, -3.0f, -3.0f});
  cam.up = {0, 1, 0};
  cam.use_fov = true;
  cam.fov_y_deg = 0.05f;
  cam.width = cam.height = 4;
  s.cameras.push_back(cam);
  return s;
}

// A w x 1 PNG, transparent (0) on its left half and opaque (255) on its right half.
std::string half_open_png() {
  const std::string path = tmp_dir("alpha_cutout") + "/half.png";
  constexpr int kW = 8;
  std::vector<uint8_t> rgb(3 * kW);
  for (int x = 0; x < kW; ++x)
    for (int c = 0; c < 3; ++c) rgb[size_t(3 * x + c)] = x < kW / 2 ? 0 : 255;
  write_png(path, rgb, kW, 1);
  return path;
}

void add_half_open_alpha(SceneDesc& s) {
  TextureDesc t;
  t.name = "half-open alpha";
  t.image_path = half_open_png();
  t.filter = TextureFilter::Nearest;
  s.textures.push_back(t);
  s.meshes[2].alpha.texture = 0;
  s.meshes[2].alpha.image.encoding = AlphaEncoding::Linear;
}

void expect_floor_radiance(const SceneDesc& s, double irradiance, const char* what) {
  const auto w = build_world(s, {});
  ASSERT_TRUE(w->features & kFeatureAlpha);
  const double want = kAlbedo / kPiD * irradiance;
  for (const char* strategy : {"nee", "brdf", "mis"}) {
    PathSettings p = kiln_strategy(strategy, PathSettings{}, "test");
    p.max_depth = 1;
    p.russian_roulette = false;
    const Estimate e = estimate_mean(*w, p, s.cameras[0], 60000);
    EXPECT_NEAR(e.mean, want, kMaxZ * e.stderr_)
        << what << ", " << strategy << ": " << e.mean << " +- " << e.stderr_ << " vs " << want;
  }
}

TEST(AlphaCutout, AnOccluderOfOpacityAPassesOneMinusAOfTheLight) {
  // At half height it covers the light (seen from the origin: [-0.25, 0.25]^2) and stays clear of the camera's ray.
  SceneDesc s = lit_floor(1.0f, 1.0f);
  s.meshes[2].alpha.value = 0.35f;
  expect_floor_radiance(s, 0.65 * 4.0 * corner_rectangle_irradiance(0.5, 0.5, kLightHeight), "opacity 0.35");
}

TEST(AlphaCutout, AHalfOpenImageLetsExactlyTheOtherHalfOfTheLightThrough) {
  // The occluder, 1.01x the light's size, sits just under it; its open half (x < 0, texels 0-3) shadows nothing,
  // its opaque half covers the light's x > 0 half exactly as seen from the origin (the boundary plane x = 0 holds
  // the origin). What is left is the light's x < 0 half: two corner rectangles 0.5 x 0.5.
  SceneDesc s = lit_floor(kLightHeight - 0.01f, 1.01f);
  add_half_open_alpha(s);
  expect_floor_radiance(s, 2.0 * corner_rectangle_irradiance(0.5, 0.5, kLightHeight), "half-open image");
}

TEST(AlphaCutout, CameraRaysSeeTheLightThroughTheOpenHalf) {
  // From the origin looking straight up through the occluder at the light: the view's left half (x < 0) sees the
  // light (kL), the right half the black occluder; the view is symmetric about x = 0.
  SceneDesc s = lit_floor(kLightHeight - 0.01f, 1.01f);
  add_half_open_alpha(s);
  CameraDesc& cam = s.cameras[0];
  cam.position = {0.0f, 0.5f, 0.0f};
  cam.gaze = {0, 1, 0};
  cam.up = {0, 0, 1};
  cam.fov_y_deg = 10.0f;
  const auto w = build_world(s, {});
  PathSettings p;
  p.max_depth = 0;
  const Estimate e = estimate_mean(*w, p, cam, 40000);
  EXPECT_NEAR(e.mean, 0.5 * kL, kMaxZ * e.stderr_) << e.mean << " +- " << e.stderr_;
}

TEST(AlphaCutout, OpaqueShapesBuildNoAlphaTest) {
  SceneDesc s = lit_floor(1.0f, 1.0f);
  s.meshes[2].alpha.value = 1.0f;  // pbrt's default: no cut-out
  const auto w = build_world(s, {});
  EXPECT_FALSE(w->features & kFeatureAlpha);
  EXPECT_FALSE(w->alpha);
  EXPECT_EQ(w->geometry.alpha.opacity, nullptr);
  for (const Shape& shape : w->geometry.shapes) EXPECT_FALSE(shape.alpha);
}

}  // namespace
}  // namespace kiln::test
