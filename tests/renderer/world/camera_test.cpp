// The camera as the CENG795 XML describes it (spec §2), through the loader: FovY and the aspect ratio, an
// asymmetric NearPlane, lookAt with GazePoint, an Up that is not perpendicular to the gaze, and the thin lens
// (a point at FocusDistance is sharp, a point off it spreads by the circle of confusion).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "renderer/render_util.h"
#include "scenes/xml_loader.h"

namespace kiln::test {
namespace {

constexpr float kPi = 3.14159265358979f;

CameraDesc load_camera(const std::string& name, const std::string& camera_xml) {
  const std::string path = tmp_dir("camera") + "/" + name + ".xml";
  std::ofstream(path) << "<Scene><Cameras>" << camera_xml << R"(</Cameras>
  <Materials><Material id="1"><DiffuseReflectance>1 1 1</DiffuseReflectance></Material></Materials>
  <VertexData>0 0 -2 1 0 -2 0 1 -2</VertexData>
  <Objects><Mesh id="1"><Material>1</Material><Faces>1 2 3</Faces></Mesh></Objects></Scene>)";
  return load_ceng795_xml(path).cameras.at(0);
}

// atan2 of the cross and dot products: acos near 1 would lose half the float digits.
float angle_between(Vec3f a, Vec3f b) { return std::atan2(length(cross(a, b)), dot(a, b)); }
float degrees_of(float rad) { return rad * 180.0f / kPi; }

// Why: FovY is the full vertical angle between the top and bottom image edges, the horizontal one follows from
// the aspect ratio; GazePoint makes the centre ray point at it; an Up tilted towards the gaze is re-orthogonalised
// (the image's vertical stays in the plane of Up and the gaze, and the horizontal is perpendicular to both).
TEST(Camera, LookAtFovYGazePointAndUpOrthogonalisation) {
  const Vec3f eye{1, 2, 3}, target{4, 2, 7};
  const Vec3f up{0.0f, 1.0f, 0.6f};  // tilted towards the gaze
  const CameraDesc cd = load_camera("lookat", R"(<Camera id="1" type="lookAt"><Position>1 2 3</Position>
    <GazePoint>4 2 7</GazePoint><Up>0 1 0.6</Up><FovY>50</FovY><NearDistance>0.5</NearDistance>
    <ImageResolution>200 100</ImageResolution><ImageName>camera.exr</ImageName></Camera>)");
  const Camera cam(cd);
  const Vec3f gaze = normalize(target - eye);
  const Ray centre = cam.generate_ray(100, 50, {0.5f, 0.5f});
  EXPECT_NEAR(dot(centre.o - eye, centre.o - eye), 0.0f, 1e-10f);
  EXPECT_NEAR(angle_between(centre.d, gaze), 0.0f, 1e-3f);
  const Ray top = cam.generate_ray(100, 0, {0.5f, 0.5f}), bottom = cam.generate_ray(100, 100, {0.5f, 0.5f});
  EXPECT_NEAR(degrees_of(angle_between(top.d, bottom.d)), 50.0f, 1e-3f);
  const Ray left = cam.generate_ray(0, 50, {0.5f, 0.5f}), right = cam.generate_ray(200, 50, {0.5f, 0.5f});
  const float half_h = std::atan(2.0f * std::tan(25.0f * kPi / 180.0f));
  EXPECT_NEAR(degrees_of(angle_between(left.d, right.d)), degrees_of(2.0f * half_h), 1e-3f);
  // Vertical: top - centre lies in the plane of up and gaze, and points up (positive along up).
  const Vec3f vertical = top.d - centre.d;
  EXPECT_NEAR(dot(normalize(vertical), normalize(cross(up, gaze))), 0.0f, 1e-4f);
  EXPECT_GT(dot(vertical, up), 0.0f);
  EXPECT_NEAR(dot(normalize(vertical), gaze), 0.0f, 0.3f);  // perpendicular to the gaze up to the perspective tilt
  // Horizontal: right - left is perpendicular to both up and gaze, and points right (gaze x up).
  const Vec3f horizontal = right.d - left.d;
  EXPECT_NEAR(dot(normalize(horizontal), normalize(up)), 0.0f, 1e-4f);
  EXPECT_NEAR(dot(normalize(horizontal), gaze), 0.0f, 1e-4f);
  EXPECT_GT(dot(horizontal, cross(gaze, up)), 0.0f);
}

// Why: NearPlane l r b t at NearDistance gives the image plane directly, asymmetric windows included.
TEST(Camera, NearPlaneSpansTheImage) {
  const CameraDesc cd = load_camera("nearplane", R"(<Camera id="1"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze>
    <Up>0 1 0</Up><NearPlane>-1 2 -0.5 1</NearPlane><NearDistance>2</NearDistance>
    <ImageResolution>30 15</ImageResolution><ImageName>camera.exr</ImageName></Camera>)");
  const Camera cam(cd);
  struct Corner {
    float x, y;
    Vec3f on_plane;
  };
  for (const Corner c : {Corner{0, 0, {-1, 1, -2}}, Corner{30, 0, {2, 1, -2}}, Corner{0, 15, {-1, -0.5f, -2}},
                         Corner{30, 15, {2, -0.5f, -2}}, Corner{10, 5, {0, 0.5f, -2}}}) {
    const Ray r = cam.generate_ray(c.x, c.y, {0.5f, 0.5f});
    EXPECT_NEAR(angle_between(r.d, c.on_plane), 0.0f, 1e-4f) << "film " << c.x << "," << c.y;
  }
}

// Where a ray crosses the plane z = -depth (the camera looks down -z from the origin).
Vec3f at_depth(const Ray& r, float depth) { return r.o + r.d * ((-depth - r.o.z) / r.d.z); }

// Why: thin lens (square aperture of side A, focus distance f): every lens sample of a pixel meets at the focus
// plane, and at depth d the lens' extent maps to a square of side A |d - f| / f (the circle of confusion).
TEST(Camera, DepthOfFieldKeepsTheFocusPlaneSharpAndBlursByTheCircleOfConfusion) {
  constexpr float kAperture = 0.2f, kFocus = 5.0f;
  const CameraDesc cd = load_camera("lens", R"(<Camera id="1"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze>
    <Up>0 1 0</Up><NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>
    <ImageResolution>64 64</ImageResolution><ImageName>camera.exr</ImageName><ApertureSize>0.2</ApertureSize><FocusDistance>5</FocusDistance>
    </Camera>)");
  const Camera cam(cd);
  ASSERT_TRUE(cam.has_aperture());
  for (const Vec2f px : {Vec2f{32, 32}, Vec2f{5.5f, 50.25f}}) {
    const Ray centre = cam.generate_ray(px.x, px.y, {0.5f, 0.5f});
    const Vec3f sharp = at_depth(centre, kFocus);
    for (const Vec2f lens : {Vec2f{0, 0}, Vec2f{1, 0}, Vec2f{0.3f, 0.9f}, Vec2f{1, 1}})
      EXPECT_NEAR(length(at_depth(cam.generate_ray(px.x, px.y, lens), kFocus) - sharp), 0.0f, 1e-5f);
    for (const float depth : {2.0f, 3.0f, 9.0f}) {
      const float coc = kAperture * std::abs(depth - kFocus) / kFocus;
      const Vec3f a = at_depth(cam.generate_ray(px.x, px.y, {0, 0.5f}), depth);
      const Vec3f b = at_depth(cam.generate_ray(px.x, px.y, {1, 0.5f}), depth);
      const Vec3f c = at_depth(cam.generate_ray(px.x, px.y, {0.5f, 0}), depth);
      const Vec3f d = at_depth(cam.generate_ray(px.x, px.y, {0.5f, 1}), depth);
      EXPECT_NEAR(std::abs(b.x - a.x), coc, 1e-5f) << "depth " << depth;
      EXPECT_NEAR(std::abs(d.y - c.y), coc, 1e-5f) << "depth " << depth;
    }
  }
  // A pinhole (no ApertureSize) has every ray from the eye.
  const Camera pinhole(load_camera("pinhole", R"(<Camera id="1"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze>
    <Up>0 1 0</Up><NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>
    <ImageResolution>64 64</ImageResolution><ImageName>camera.exr</ImageName></Camera>)"));
  EXPECT_FALSE(pinhole.has_aperture());
  EXPECT_EQ(length(pinhole.generate_ray(3, 7, {0, 1}).o), 0.0f);
}

// Why: the render must take its rays through the lens, not only the camera: the image of a sharp edge out of focus
// (the background, 1, left of x = 0; a black quad right of it, at depth 2 with the focus at 5) is blurred over the
// circle of confusion, 1 x 3 / 5 = 0.6 units there, about 5 pixels. The expected pixel is the share of its rays that
// pass left of the edge, over a grid of film positions and lens points through Camera::generate_ray (whose thin-lens
// geometry the test above checks); a render that dropped the lens sample would show a sharp edge.
TEST(Camera, RenderedEdgeOutOfFocusIsBlurredByTheLens) {
  constexpr float kDepth = 2.0f;
  constexpr int kWidth = 32, kHeight = 2, kGrid = 64;
  constexpr uint32_t kSpp = 1024;
  SceneDesc s = lambertian_scene(0.0f);
  s.background = Rgb(1.0f);
  MeshDesc quad;
  quad.name = "right half";
  quad.positions = {{0, -50, -kDepth}, {50, -50, -kDepth}, {50, 50, -kDepth}, {0, 50, -kDepth}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 0;
  s.meshes.push_back(quad);
  CameraDesc cd;
  cd.id = "1";
  cd.near_plane = {-1, 1, -1.0f / 16, 1.0f / 16};
  cd.width = kWidth;
  cd.height = kHeight;
  cd.aperture_size = 1.0f;
  cd.focus_distance = 5.0f;
  s.cameras.push_back(cd);
  const auto w = build_world(s, {});
  const Image img = render_image(*w, cd, scene_settings(cd, s, w->features), kSpp, 5);
  const Camera cam(cd);
  int blurred = 0;
  for (int x = 0; x < kWidth; ++x) {
    double bright = 0;  // the edge is vertical: only the film's and the lens' x matter
    for (int i = 0; i < kGrid; ++i)
      for (int k = 0; k < kGrid; ++k) {
        const Ray r = cam.generate_ray(float(x) + (float(i) + 0.5f) / kGrid, 1.0f, {(float(k) + 0.5f) / kGrid, 0.5f});
        bright += at_depth(r, kDepth).x < 0.0f;
      }
    const double expected = bright / (kGrid * kGrid);
    const double se = std::sqrt(std::max(expected * (1 - expected), 1.0 / kSpp) / kSpp);
    for (int y = 0; y < kHeight; ++y)
      EXPECT_NEAR(img.at(x, y).g, expected, 5 * se + 0.01) << "pixel " << x << "," << y;
    blurred += expected > 0.05 && expected < 0.95;
  }
  EXPECT_GE(blurred, 4) << "the edge spreads over the circle of confusion";
}

}  // namespace
}  // namespace kiln::test
