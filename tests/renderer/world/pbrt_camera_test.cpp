// pbrt-v4's cameras read from pbrt files, against where pbrt-v4's definitions (cameras.cpp, the file-format
// documentation) send known rays: the orthographic camera's parallel rays from the screen window and its lens
// focused on a plane, the perspective camera's screenwindow and frameaspectratio, the spherical camera's
// equirectangular directions and its equal-area film (equal pixel counts for equal solid angles), the film's
// imaging ratio, and a moving camera's pose at the shutter's ends and in between.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/error.h"
#include "renderer/render_util.h"

namespace kiln::test {
namespace {

constexpr float kTol = 1e-4f;

SceneDesc load_pbrt_text(const std::string& name, const std::string& options) {
  const std::string path = tmp_dir("pbrt_camera") + "/" + name + ".pbrt";
  std::ofstream(path) << options << "\nWorldBegin\nShape \"sphere\"\n";
  return load_scene(path);
}

void expect_near(Vec3f a, Vec3f b, float tol, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

// pbrt's LookAt frame: forward, right = up x forward (pbrt's camera space is left-handed), up' = forward x right.
struct PbrtFrame {
  Vec3f eye, right, up, forward;
};
PbrtFrame look_at(Vec3f eye, Vec3f target, Vec3f up) {
  const Vec3f f = normalize(target - eye);
  const Vec3f r = normalize(cross(normalize(up), f));
  return {eye, r, cross(f, r), f};
}

// bump-cameras.pbrt's camera: rays along the view direction from the screen window [-5, 5] x [-3.75, 3.75] spread
// over the film (raster x to camera +x, raster y down).
TEST(PbrtCamera, OrthographicRaysRunParallelFromTheScreenWindow) {
  const SceneDesc s = load_pbrt_text("ortho", R"(LookAt 0 -10 6  0 0 1  0 0 1
Camera "orthographic" "float screenwindow" [ -5 5 -3.75 3.75 ]
Film "rgb" "integer xresolution" [ 480 ] "integer yresolution" [ 360 ])");
  const Camera cam(s.cameras.at(0));
  const PbrtFrame f = look_at({0, -10, 6}, {0, 0, 1}, {0, 0, 1});
  for (const auto& [x, y] : {std::pair{0.0f, 0.0f}, {480.0f, 360.0f}, {240.0f, 180.0f}, {120.5f, 300.25f}}) {
    const Ray r = cam.generate_ray(x, y, {0.5f, 0.5f});
    const Vec3f expected = f.eye + f.right * (-5.0f + 10.0f * x / 480.0f) + f.up * (3.75f - 7.5f * y / 360.0f);
    expect_near(r.o, expected, kTol, "origin at " + std::to_string(x) + "," + std::to_string(y));
    expect_near(r.d, f.forward, kTol, "direction");
  }
}

// pbrt's orthographic lens: from a point of the disk of radius lensradius around the eye, through the screen point
// carried to the focus plane (focaldistance along the view direction).
TEST(PbrtCamera, OrthographicLensAimsAtTheFocusPlane) {
  const SceneDesc s = load_pbrt_text("ortho_lens", R"(LookAt 0 0 0  0 0 1  0 1 0
Camera "orthographic" "float screenwindow" [ -2 2 -1 1 ] "float lensradius" [ 0.25 ] "float focaldistance" [ 8 ]
Film "rgb" "integer xresolution" [ 200 ] "integer yresolution" [ 100 ])");
  const Camera cam(s.cameras.at(0));
  const PbrtFrame f = look_at({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
  const Vec3f focus = f.right * (-2.0f + 4.0f * 30.0f / 200.0f) + f.up * (1.0f - 2.0f * 70.0f / 100.0f) + f.forward * 8.0f;
  for (const Vec2f u : {Vec2f(0.1f, 0.2f), Vec2f(0.9f, 0.5f), Vec2f(0.5f, 0.99f), Vec2f(0.0f, 0.0f)}) {
    const Ray r = cam.generate_ray(30.0f, 70.0f, u);
    EXPECT_LE(length(r.o), 0.25f + kTol) << "on the lens disk";
    EXPECT_NEAR(dot(r.o, f.forward), 0.0f, kTol) << "in the plane of the eye";
    const float t = dot(focus - r.o, f.forward) / dot(r.d, f.forward);
    expect_near(r.o + r.d * t, focus, 1e-3f, "through the focus point");
  }
}

// screenwindow [-1 1 -1 1] on a 2:1 film stretches the square window over it; frameaspectratio 4 on a square film
// widens the default window to [-4, 4] x [-1, 1]. Directions at depth 1 are the window times tan(fov / 2).
TEST(PbrtCamera, PerspectiveScreenWindowAndFrameAspectRatio) {
  const float t = std::tan(radians(30.0f));
  const PbrtFrame f = look_at({1, 2, 3}, {1, 2, 10}, {0, 1, 0});
  const auto camera_dir = [&](Vec3f c) { return normalize(f.right * c.x + f.up * c.y + f.forward * c.z); };
  {
    const SceneDesc s = load_pbrt_text("window", R"(LookAt 1 2 3  1 2 10  0 1 0
Camera "perspective" "float fov" [ 60 ] "float screenwindow" [ -1 1 -1 1 ]
Film "rgb" "integer xresolution" [ 200 ] "integer yresolution" [ 100 ])");
    const Camera cam(s.cameras.at(0));
    expect_near(cam.generate_ray(0, 0, {0.5f, 0.5f}).d, camera_dir({-t, t, 1}), kTol, "top left");
    expect_near(cam.generate_ray(200, 100, {0.5f, 0.5f}).d, camera_dir({t, -t, 1}), kTol, "bottom right");
  }
  {
    const SceneDesc s = load_pbrt_text("aspect", R"(LookAt 1 2 3  1 2 10  0 1 0
Camera "perspective" "float fov" [ 60 ] "float frameaspectratio" [ 4 ]
Film "rgb" "integer xresolution" [ 100 ] "integer yresolution" [ 100 ])");
    const Camera cam(s.cameras.at(0));
    expect_near(cam.generate_ray(0, 50, {0.5f, 0.5f}).d, camera_dir({-4 * t, 0, 1}), kTol, "left edge");
    expect_near(cam.generate_ray(50, 0, {0.5f, 0.5f}).d, camera_dir({0, t, 1}), kTol, "top edge");
  }
}

// pbrt's equirectangular film: theta = pi y / height from camera +y (up), phi = 2 pi x / width from camera +x
// towards camera +z (the view direction) at a quarter of the width.
TEST(PbrtCamera, SphericalEquirectangularDirections) {
  const SceneDesc s = load_pbrt_text("equirect", R"(LookAt 0 0 0  0 0 -1  0 1 0
Camera "spherical" "string mapping" "equirectangular"
Film "rgb" "integer xresolution" [ 400 ] "integer yresolution" [ 200 ])");
  const Camera cam(s.cameras.at(0));
  const PbrtFrame f = look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0});
  expect_near(cam.generate_ray(0, 100, {}).d, f.right, kTol, "phi 0");
  expect_near(cam.generate_ray(100, 100, {}).d, f.forward, kTol, "phi pi/2");
  expect_near(cam.generate_ray(200, 100, {}).d, -f.right, kTol, "phi pi");
  expect_near(cam.generate_ray(300, 100, {}).d, -f.forward, kTol, "phi 3pi/2");
  expect_near(cam.generate_ray(123, 0, {}).d, f.up, kTol, "top row");
  expect_near(cam.generate_ray(77, 200, {}).d, -f.up, kTol, "bottom row");
  const Vec3f d = cam.generate_ray(150, 50, {}).d;  // theta pi/4, phi 3 pi / 4
  expect_near(d, normalize(f.up * 1.0f + (f.right * std::cos(0.75f * kPi) + f.forward * std::sin(0.75f * kPi))), kTol,
              "theta pi/4, phi 3pi/4");
}

// The equal-area film: the share of pixels whose ray falls in a cone is the cone's share of the sphere,
// (1 - cos a) / 2, wherever the cone points (the latitude-longitude film crowds pixels at its poles instead).
TEST(PbrtCamera, SphericalEqualAreaPixelsCoverEqualSolidAngles) {
  const SceneDesc s = load_pbrt_text("equalarea", R"(LookAt 0 0 0  0 0 1  0 1 0
Camera "spherical"
Film "rgb" "integer xresolution" [ 256 ] "integer yresolution" [ 256 ])");
  const Camera cam(s.cameras.at(0));
  expect_near(cam.generate_ray(128, 128, {}).d, Vec3f(0, 1, 0), kTol, "the square's centre is up");
  const float cos_a = std::cos(radians(30.0f));
  const double expected = (1.0 - cos_a) / 2.0;
  for (const Vec3f axis : {Vec3f(0, 1, 0), Vec3f(0, 0, 1), normalize(Vec3f(1, -1, 0.3f))}) {
    int inside = 0;
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x)
        inside += dot(cam.generate_ray(float(x) + 0.5f, float(y) + 0.5f, {}).d, axis) >= cos_a;
    const double share = inside / (256.0 * 256.0);
    // Pixels on the cone's edge: about its perimeter in pixels, ~2.5% of the count here.
    EXPECT_NEAR(share / expected, 1.0, 0.03) << "axis " << axis.x << " " << axis.y << " " << axis.z;
  }
}

// Film "iso" 400 with shutter 0.25..0.75 scales every sample by 400/100 * 0.5 = 2 (pbrt's imaging ratio); a
// "gbuffer" film asks for the AOV layers.
TEST(PbrtCamera, ImagingRatioAndGbufferFilm) {
  const SceneDesc s = load_pbrt_text("iso", R"(Camera "perspective" "float shutteropen" [ 0.25 ] "float shutterclose" [ 0.75 ]
Film "gbuffer" "float iso" [ 400 ] "integer xresolution" [ 8 ] "integer yresolution" [ 8 ])");
  const Camera cam(s.cameras.at(0));
  EXPECT_FLOAT_EQ(cam.sample(4, 4, {0.5f, 0.5f}).weight, 2.0f);
  EXPECT_TRUE(s.cameras.at(0).aov_layers);
}

// Film "maxcomponentvalue" scales a sample whose largest channel is above it down to it, keeping its hue (pbrt-v4's
// RGBFilm): under a uniform sky of L = (8, 4, 2) every sample, and so every pixel, is (2, 1, 0.5) with the limit 2,
// stays (8, 4, 2) with the limit 10 or without one; the limit applies after the film's imaging ratio (iso 200
// doubles the sky to (16, 8, 4) before the limit 10 brings it to (10, 5, 2.5)).
TEST(PbrtCamera, MaxComponentValueClampsEachSampleKeepingItsHue) {
  const auto sky_pixel = [](const std::string& name, const std::string& film_params) {
    const std::string path = tmp_dir("pbrt_camera") + "/" + name + ".pbrt";
    std::ofstream(path) << "Camera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" [ 4 ] "
                           "\"integer yresolution\" [ 4 ] "
                        << film_params << "\nWorldBegin\nLightSource \"infinite\" \"rgb L\" [ 8 4 2 ]\n";
    const SceneDesc scene = load_scene(path);
    const Image image = render_like_kiln(scene, *build_scene_world(scene), 4, 1);
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        EXPECT_NEAR(image.at(x, y).max_component(), image.at(0, 0).max_component(), 1e-5f) << name << " pixel " << x
                                                                                              << "," << y;
    return image.at(0, 0);
  };
  const auto expect_rgb = [](Rgb got, Rgb want, const std::string& what) {
    EXPECT_FLOAT_EQ(got.r, want.r) << what;
    EXPECT_FLOAT_EQ(got.g, want.g) << what;
    EXPECT_FLOAT_EQ(got.b, want.b) << what;
  };
  expect_rgb(sky_pixel("unclamped", ""), Rgb(8, 4, 2), "no limit");
  expect_rgb(sky_pixel("above", "\"float maxcomponentvalue\" [ 10 ]"), Rgb(8, 4, 2), "under the limit");
  expect_rgb(sky_pixel("clamped", "\"float maxcomponentvalue\" [ 2 ]"), Rgb(2, 1, 0.5f), "limit 2");
  expect_rgb(sky_pixel("iso", "\"float iso\" [ 200 ] \"float maxcomponentvalue\" [ 10 ]"), Rgb(10, 5, 2.5f),
             "imaging ratio, then the limit");
  const std::string bad = tmp_dir("pbrt_camera") + "/bad_max.pbrt";
  std::ofstream(bad) << "Film \"rgb\" \"float maxcomponentvalue\" [ -1 ]\nWorldBegin\n";
  try {
    (void)load_scene(bad);
    ADD_FAILURE() << "a negative maxcomponentvalue must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad_max.pbrt: line 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("\"maxcomponentvalue\" must be positive"), std::string::npos) << e.what();
  }
}

// ActiveTransform on the camera: at the shutter's ends the camera is at its two poses, half way it has moved half
// the distance and turned half the angle (pbrt's interpolation). TransformTimes 0 2 with the shutter 0..1 stops
// the motion half way through.
TEST(PbrtCamera, MovingCameraInterpolatesItsPose) {
  const SceneDesc s = load_pbrt_text("moving", R"(ActiveTransform StartTime
LookAt 0 0 0  0 0 1  0 1 0
ActiveTransform EndTime
LookAt 4 0 0  4 1 0  0 0 -1
ActiveTransform All
Camera "perspective" "float fov" [ 45 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ])");
  ASSERT_TRUE(s.cameras.at(0).motion);
  const Camera cam(s.cameras.at(0));
  ASSERT_TRUE(cam.moves());
  const auto centre = [&](float t) { return cam.sample(8, 8, {0.5f, 0.5f}, t).ray; };
  expect_near(centre(0).o, {0, 0, 0}, kTol, "start position");
  expect_near(centre(0).d, {0, 0, 1}, kTol, "start direction");
  expect_near(centre(0.999999f).d, {0, 1, 0}, 1e-3f, "end direction");
  expect_near(centre(0.5f).o, {2, 0, 0}, kTol, "half way");
  expect_near(centre(0.5f).d, normalize(Vec3f(0, 1, 1)), 1e-3f, "half the turn");
  EXPECT_FLOAT_EQ(centre(0.25f).time, 0.25f);

  const SceneDesc slow = load_pbrt_text("moving_slow", "TransformTimes 0 2\n" + std::string(R"(ActiveTransform StartTime
LookAt 0 0 0  0 0 1  0 1 0
ActiveTransform EndTime
LookAt 4 0 0  4 1 0  0 0 -1
ActiveTransform All
Camera "perspective" "float fov" [ 45 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ])"));
  const Camera half(slow.cameras.at(0));
  expect_near(half.sample(8, 8, {0.5f, 0.5f}, 0.999999f).ray.o, {2, 0, 0}, 1e-3f, "TransformTimes 0 2: half way at close");
}

}  // namespace
}  // namespace kiln::test
