// pbrt's motion (ActiveTransform, TransformTimes) through the loader, the world and both accelerators, against
// where the moving shapes are at each instant:
//   * a bar turning a quarter turn (pbrt's slerp: constant angular speed) seen by an orthographic camera looking
//     straight down covers a pixel exactly when the closed form says it does, ray by ray at stratified times;
//   * a sphere that moves and grows (translation and stretch interpolated linearly) likewise, and the quadrics: a
//     turning half annulus, a sliding cylinder, a turning sphere half cut away by its alpha texture, and shapes
//     turning through a 3-D alpha texture that stays put;
//   * killeroo-moving (the pbrt-v4 collection's scene, at a lower resolution): at every instant the moving scene
//     is hit where a static scene with the killeroos placed at that instant is hit, and its coverage averaged over
//     the shutter is the average of those static frames;
// each with Embree and with the in-house BVH.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "renderer/accel/surface_point.h"
#include "renderer/render_util.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

constexpr int kTimes = 32;  // stratified shutter times per pixel
constexpr int kRes = 48;
// A sample this close (in the closed form's own units) to a shape's edge may go either way in float.
constexpr double kEdgeBand = 1e-4;

std::string write_scene(const std::string& name, const std::string& text) {
  const std::string path = tmp_dir("pbrt_motion") + "/" + name + ".pbrt";
  std::ofstream(path) << text;
  return path;
}

std::unique_ptr<World> world_for(const SceneDesc& s, AccelKind accel) {
  WorldOptions wo;
  wo.accel = accel;
  return build_world(s, wo);
}

float stratified_time(int k) { return (float(k) + 0.5f) / float(kTimes); }

// An orthographic camera 10 above the plane z = 0 looking down, seeing [-1, 1]^2; a pixel centre's ray meets the
// plane at (x, y).
const char* kTopView = R"(LookAt 0 0 10  0 0 0  0 1 0
Camera "orthographic" "float screenwindow" [ -1 1 -1 1 ]
Film "rgb" "integer xresolution" [ 48 ] "integer yresolution" [ 48 ]
WorldBegin
)";

// Compares, for every pixel centre and stratified time, whether the accelerator's ray hits against `covered(x, y,
// t)`, a signed distance to the shape's edge (>= 0 inside). Samples within kEdgeBand of the edge are skipped.
template <typename Covered>
void expect_hits_match(const World& w, const Camera& cam, Covered&& covered, const char* what) {
  int checked = 0, mismatched = 0, hits = 0;
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x)
      for (int k = 0; k < kTimes; ++k) {
        const float t = stratified_time(k);
        const Ray r = cam.sample(float(x) + 0.5f, float(y) + 0.5f, {0.5f, 0.5f}, t).ray;
        const double d = covered(double(r.o.x), double(r.o.y), double(t));
        if (std::abs(d) < kEdgeBand) continue;
        Hit h;
        const bool hit = w.accel->intersect(r, h);
        ++checked;
        hits += hit;
        mismatched += hit != (d > 0.0);
        ASSERT_EQ(hit, w.accel->occluded(r)) << what << ": intersect and occluded disagree";
      }
  EXPECT_EQ(mismatched, 0) << what << ": " << mismatched << " of " << checked << " samples";
  EXPECT_GT(hits, checked / 20) << what << ": the shape is in view";
}

// Runs check(world, name) on the scene's world built with each accelerator, its moving shapes moving.
template <typename Check>
void with_each_accelerator(const SceneDesc& s, Check&& check) {
  for (AccelKind accel : {AccelKind::Embree, AccelKind::Bvh}) {
    const auto w = world_for(s, accel);
    ASSERT_TRUE(w->features & kFeatureMotionBlur);
    check(*w, accel == AccelKind::Embree ? "embree" : "bvh");
  }
}

// expect_hits_match for camera 0 of the scene with each accelerator.
template <typename Covered>
void expect_coverage(const SceneDesc& s, Covered&& covered) {
  const Camera cam(s.cameras.at(0));
  with_each_accelerator(s, [&](const World& w, const char* name) { expect_hits_match(w, cam, covered, name); });
}

// A bar 4 long and 0.2 wide, turned from 0 to 90 degrees about z over the shutter (ActiveTransform EndTime): at time
// t it lies along angle pi t / 2, and covers (x, y) when the point's distance from its axis is at most 0.1.
TEST(PbrtMotion, TurningBarCoversWhatTheSlerpSays) {
  const SceneDesc s = load_scene(write_scene("bar", std::string(kTopView) + R"(AttributeBegin
ActiveTransform EndTime
Rotate 90 0 0 1
ActiveTransform All
Shape "trianglemesh" "point3 P" [ -2 -0.1 0  2 -0.1 0  2 0.1 0  -2 0.1 0 ] "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd
)"));
  expect_coverage(s, [](double x, double y, double t) {
    const double a = 0.5 * 3.14159265358979323846 * t;
    return 0.1 - std::abs(-x * std::sin(a) + y * std::cos(a));
  });
}

// Quadrics move by their animated transform as spheres do. A half annulus (radii 0.2 to 0.8, phi in [0, pi]: object
// y >= 0) turned a quarter turn about z covers (x, y) at time t when its radius is in the ring and its distance from
// the turned x axis, -x sin a + y cos a with a = pi t / 2, is positive.
TEST(PbrtMotion, TurningHalfAnnulusCoversWhatTheSlerpSays) {
  const SceneDesc s = load_scene(write_scene("disk", std::string(kTopView) + R"(AttributeBegin
ActiveTransform EndTime
Rotate 90 0 0 1
ActiveTransform All
Shape "disk" "float radius" 0.8 "float innerradius" 0.2 "float phimax" 180
AttributeEnd
)"));
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  expect_coverage(s, [](double x, double y, double t) {
    const double a = 0.5 * 3.14159265358979323846 * t, r = std::hypot(x, y);
    return std::min({0.8 - r, r - 0.2, -x * std::sin(a) + y * std::cos(a)});
  });
}

// A cylinder of radius 0.2 from x = -0.6 to 0.6 (its axis turned onto x), moving from y = -0.3 to y = 0.2: at time t
// it covers |x| <= 0.6, |y - (-0.3 + 0.5 t)| <= 0.2 from above.
TEST(PbrtMotion, SlidingCylinderCoversWhatTheBlendSays) {
  const SceneDesc s = load_scene(write_scene("cylinder", std::string(kTopView) + R"(AttributeBegin
Translate 0 -0.3 0
ActiveTransform EndTime
Translate 0 0.5 0
ActiveTransform All
Rotate 90 0 1 0
Shape "cylinder" "float radius" 0.2 "float zmin" -0.6 "float zmax" 0.6
AttributeEnd
)"));
  const Camera cam(s.cameras.at(0));
  const auto axis_y = [](double t) { return -0.3 + 0.5 * t; };
  const auto covered = [&](double x, double y, double t) {
    return std::min(0.6 - std::abs(x), 0.2 - std::abs(y - axis_y(t)));
  };
  expect_coverage(s, covered);
  // The shading point and normal are the cylinder's where it is at the ray's time.
  with_each_accelerator(s, [&](const World& w, const char* name) {
    for (int k = 0; k < kTimes; ++k) {
      const float t = stratified_time(k);
      const Ray r = cam.sample(24.5f, float(kRes) * (1.0f - float(axis_y(t) + 1.0) / 2.0f), {0.5f, 0.5f}, t).ray;
      Hit h;
      ASSERT_TRUE(w.accel->intersect(r, h)) << name << ", time " << t;
      const SurfacePoint sp = surface_point<false>(w.geometry, r, h);
      const Vec3f radial(0.0f, sp.p.y - float(axis_y(t)), sp.p.z);
      EXPECT_NEAR(length(radial), 0.2f, 1e-4f) << name << ", time " << t;
      EXPECT_GT(dot(sp.ng, normalize(radial)), 0.9999f) << name << ", time " << t;
    }
  });
}

// A sphere of radius 0.5 whose alpha texture cuts away phi in [pi, 2 pi) (a checkerboard of two cells along u: pbrt's
// tex1 = 1 on the first, tex2 = 0 on the second) is built as a quadric; turned a quarter turn about z it covers the
// half disk on the positive side of the turned x axis, both of its crossings cut alike.
TEST(PbrtMotion, TurningAlphaCutSphereCoversItsUncutHalf) {
  const SceneDesc s = load_scene(write_scene("cut_sphere", std::string(kTopView) + R"(AttributeBegin
ActiveTransform EndTime
Rotate 90 0 0 1
ActiveTransform All
Texture "half" "float" "checkerboard" "float uscale" 2 "float vscale" 1
Shape "sphere" "float radius" 0.5 "texture alpha" "half"
AttributeEnd
)"));
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_EQ(world_for(s, AccelKind::Embree)->stats.quadrics, 1u) << "the cut sphere is a quadric";
  expect_coverage(s, [](double x, double y, double t) {
    const double a = 0.5 * 3.14159265358979323846 * t;
    return std::min(0.5 - std::hypot(x, y), -x * std::sin(a) + y * std::cos(a));
  });
}

// pbrt-v4 evaluates alpha where the hit is at the ray's time, so a 3-D alpha texture stays put in space while a
// shape turns through it. The checkerboard here (cells of 10, offset so that |x|, |z| < 5 share one cell) keeps world
// y >= 0 and cuts y < 0: a turning sphere of radius 0.5 and the turning bar both show only their y >= 0 parts, at
// every instant.
TEST(PbrtMotion, TurningShapesAreCutWhereTheSpaceFixedAlphaTextureSays) {
  const std::string texture = R"(AttributeBegin
Scale 10 10 10
Translate -0.5 0 -0.5
Texture "upper" "float" "checkerboard" "integer dimension" 3
AttributeEnd
AttributeBegin
ActiveTransform EndTime
Rotate 90 0 0 1
ActiveTransform All
)";
  const SceneDesc sphere = load_scene(write_scene("alpha3d_sphere", std::string(kTopView) + texture + R"(
Shape "sphere" "float radius" 0.5 "texture alpha" "upper"
AttributeEnd
)"));
  EXPECT_TRUE(sphere.warnings.empty()) << sphere.warnings.front();
  expect_coverage(sphere, [](double x, double y, double) { return std::min(0.5 - std::hypot(x, y), y); });
  const SceneDesc bar = load_scene(write_scene("alpha3d_bar", std::string(kTopView) + texture + R"(
Shape "trianglemesh" "point3 P" [ -2 -0.1 0  2 -0.1 0  2 0.1 0  -2 0.1 0 ] "integer indices" [ 0 1 2 0 2 3 ]
  "texture alpha" "upper"
AttributeEnd
)"));
  expect_coverage(bar, [](double x, double y, double t) {
    const double a = 0.5 * 3.14159265358979323846 * t;
    return std::min(0.1 - std::abs(-x * std::sin(a) + y * std::cos(a)), y);
  });
}

// A sphere of radius 0.3 at (-0.5, 0) moving to (0.5, 0.2) while scaled by 2: at time t its centre and radius are
// the linear blends, and it covers (x, y) within that radius of the centre.
TEST(PbrtMotion, MovingGrowingSphereCoversWhatTheBlendSays) {
  const SceneDesc s = load_scene(write_scene("sphere", std::string(kTopView) + R"(AttributeBegin
Translate -0.5 0 0
ActiveTransform EndTime
Translate 1 0.2 0
Scale 2 2 2
ActiveTransform All
Shape "sphere" "float radius" 0.3
AttributeEnd
)"));
  expect_coverage(s, [](double x, double y, double t) {
    const double cx = -0.5 + t, cy = 0.2 * t, r = 0.3 * (1.0 + t);
    return r - std::hypot(x - cx, y - cy);
  });
}

// killeroo-moving.pbrt as in the pbrt-v4 collection (camera, light, floor and wall, the two killeroos and their
// ActiveTransform blocks), at kRes x kRes. `at`: the killeroos placed at that instant instead of moving (both
// only translate: the start transform adds Translate 35 35 35, the second one also Translate 30 0 0).
std::string killeroo_moving(const std::string& geometry, std::optional<float> at) {
  const auto first = [&] {
    if (!at) return std::string("ActiveTransform StartTime\nTranslate 35 35 35\n");
    const float s = 35.0f * (1.0f - *at);
    return "Translate " + std::to_string(s) + " " + std::to_string(s) + " " + std::to_string(s) + "\n";
  };
  const auto second = [&] {
    if (!at) return std::string("ActiveTransform StartTime\nTranslate 30 0 0\nActiveTransform All\n");
    return "Translate " + std::to_string(30.0f * (1.0f - *at)) + " 0 0\n";
  };
  return R"(LookAt 400 20 30  0 63 -110  0 0 1
Rotate -5 0 0 1
Camera "perspective" "float fov" [ 39 ]
Film "rgb" "string filename" [ "killeroo-moving.exr" ] "integer yresolution" [ 48 ] "integer xresolution" [ 48 ]
Sampler "halton" "integer pixelsamples" [ 512 ]
WorldBegin
AttributeBegin
  Material "diffuse" "rgb reflectance" [ 0 0 0 ]
  Translate 150 0 20
  Translate 0 120 0
  AreaLightSource "diffuse" "rgb L" [ 2000 2000 2000 ]
  Shape "sphere" "float radius" [ 3 ]
AttributeEnd
AttributeBegin
  Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.8 ]
  Translate 0 0 -140
  Shape "trianglemesh" "point2 uv" [ 0 0 5 0 5 5 0 5 ] "integer indices" [ 0 1 2 2 3 0 ]
      "point3 P" [ -1000 -1000 0 1000 -1000 0 1000 1000 0 -1000 1000 0 ]
  Shape "trianglemesh" "point2 uv" [ 0 0 5 0 5 5 0 5 ] "integer indices" [ 0 1 2 2 3 0 ]
      "point3 P" [ -400 -1000 -1000 -400 1000 -1000 -400 1000 1000 -400 -1000 1000 ]
AttributeEnd
AttributeBegin
  Scale 0.5 0.5 0.5
  Rotate -60 0 0 1
  Material "coateddiffuse" "float roughness" [ 0.025 ] "rgb reflectance" [ 0.4 0.2 0.2 ]
  Translate 100 200 -140
)" + first() + R"(  AttributeBegin
    Include ")" + geometry + R"("
  AttributeEnd
  Material "coateddiffuse" "float roughness" [ 0.15 ] "rgb reflectance" [ 0.4 0.5 0.4 ]
  AttributeBegin
)" + second() + R"(    Translate -200 0 0
    Include ")" + geometry + R"("
  AttributeEnd
AttributeEnd
)";
}

// Which shape a ray hits, as a class: 0 nothing, 1 a killeroo (an instance when moving, a mesh when static), 2 the
// floor, wall or light.
int hit_class(const World& w, const Ray& r) {
  Hit h;
  if (!w.accel->intersect(r, h)) return 0;
  const Shape& s = w.geometry.shapes[h.shape];
  const bool killeroo = s.kind == ShapeKind::Instance || (s.kind == ShapeKind::Mesh && w.geometry.meshes[s.index].triangle_count() > 2);
  return killeroo ? 1 : 2;
}

TEST(PbrtMotion, KillerooMovingCoverageIsTheShutterAverageOfStaticFrames) {
  const std::string geometry = shared_dir() + "/scenes/pbrt/killeroos/geometry/killeroo.pbrt";
  KILN_NEED_SHARED_PATH(geometry);
  const SceneDesc moving = load_scene(write_scene("killeroo_moving", killeroo_moving(geometry, std::nullopt)));
  ASSERT_EQ(moving.instances.size(), 2u) << "both killeroos move";
  const Camera cam(moving.cameras.at(0));
  for (AccelKind accel : {AccelKind::Embree, AccelKind::Bvh}) {
    const char* name = accel == AccelKind::Embree ? "embree" : "bvh";
    const auto w = world_for(moving, accel);
    std::vector<double> moving_coverage(size_t(kRes * kRes), 0.0), static_coverage(moving_coverage.size(), 0.0);
    int samples = 0, disagree = 0;
    for (int k = 0; k < kTimes; k += 4) {  // 8 static frames
      const float t = stratified_time(k);
      const SceneDesc frame = load_scene(write_scene("killeroo_at", killeroo_moving(geometry, t)));
      const auto ws = world_for(frame, accel);
      for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
          const Ray r = cam.sample(float(x) + 0.5f, float(y) + 0.5f, {0.5f, 0.5f}, t).ray;
          const int a = hit_class(*w, r), b = hit_class(*ws, r);
          ++samples;
          disagree += a != b;
          moving_coverage[size_t(y * kRes + x)] += a == 1;
          static_coverage[size_t(y * kRes + x)] += b == 1;
        }
    }
    // Rays that graze a silhouette may go either way between an instance and a flattened mesh.
    EXPECT_LE(disagree, samples / 500) << name << ": " << disagree << " of " << samples << " rays";
    double covered = 0, diff = 0;
    for (size_t i = 0; i < moving_coverage.size(); ++i) {
      covered += static_coverage[i];
      diff += std::abs(moving_coverage[i] - static_coverage[i]);
    }
    EXPECT_GT(covered, 0.05 * samples) << name << ": the killeroos are in view";
    EXPECT_LE(diff, 0.002 * covered) << name;
  }
}

}  // namespace
}  // namespace kiln::test
