// Shading normals at renderer level: a flat floor whose per-vertex normals lean 36.87 degrees away from the face
// normal, lit by a point light straight above the point the camera sees. The Lambertian radiance a/pi I/d^2 cos is
// taken about the shading normal (cos = 0.8), not the geometric one (1). An instance of the same mesh under a
// non-uniform scale carries its normals by the inverse transpose (cos = 0.5547; the forward matrix would give 0.936),
// and a mesh flagged smooth without normals gets area-weighted vertex normals.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/render_util.h"
#include "renderer/world/interaction.h"

namespace kiln::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kAlbedo = 0.5f;
constexpr float kIntensity = 4.0f;
constexpr float kLightHeight = 2.0f;
constexpr double kRelTol = 2e-4;  // delta light: no Monte Carlo noise
const Vec3f kTilted = normalize(Vec3f{0.6f, 0.0f, 0.8f});

SceneDesc floor_scene() {
  SceneDesc s = lambertian_scene(kAlbedo);
  s.point_lights.push_back({{0.0f, 0.0f, kLightHeight}, Rgb(kIntensity)});
  CameraDesc cam;
  cam.id = "1";
  cam.position = {0.0f, -3.0f, 3.0f};
  cam.gaze = normalize(Vec3f{0.0f, 3.0f, -3.0f});
  cam.up = {0, 0, 1};
  cam.use_fov = true;
  cam.fov_y_deg = 0.2f;
  cam.width = cam.height = 4;
  s.cameras.push_back(cam);
  return s;
}

MeshDesc floor_mesh(bool with_normals) {
  MeshDesc floor;
  floor.name = "floor";
  floor.positions = {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};
  floor.indices = {0, 1, 2, 0, 2, 3};  // +z
  if (with_normals) floor.normals.assign(4, kTilted);
  floor.material = 0;
  return floor;
}

double expected_radiance(double cos_shading) {
  return kAlbedo / kPi * kIntensity / (kLightHeight * kLightHeight) * cos_shading;
}

void expect_radiance(const SceneDesc& s, double cos_shading, const char* what) {
  const auto w = build_world(s, {});
  PathSettings kiln;
  kiln.max_depth = 1;
  kiln.russian_roulette = false;
  const double want = expected_radiance(cos_shading);
  for (const auto& [name, settings] :
       {std::pair<const char*, IntegratorSettings>{"kiln", kiln}, {"course ray tracer", CourseRaySettings{}}}) {
    const Estimate e = estimate_mean(*w, settings, s.cameras[0], 2000);
    EXPECT_NEAR(e.mean, want, kRelTol * want) << what << ", " << name << " (geometric normal: " << expected_radiance(1)
                                              << ")";
  }
}

TEST(ShadingNormals, MeshVertexNormalsShadeTheSurface) {
  SceneDesc s = floor_scene();
  s.meshes.push_back(floor_mesh(true));
  expect_radiance(s, kTilted.z, "mesh normals");
  // The same floor without normals is shaded by its face normal.
  SceneDesc flat = floor_scene();
  flat.meshes.push_back(floor_mesh(false));
  expect_radiance(flat, 1.0, "flat");
}

TEST(ShadingNormals, InstanceNormalsFollowTheInverseTranspose) {
  SceneDesc s = floor_scene();
  MeshDesc base = floor_mesh(true);
  s.meshes.push_back(base);
  s.meshes.back().is_instance_base = true;
  s.meshes.back().visible = false;
  InstanceDesc in;
  in.name = "scaled floor";
  in.base_mesh = 0;
  in.material = 0;
  // Scaling z by 2 keeps the plane at z = 0 and tilts the normals further.
  in.to_world = Transform::scale({1, 1, 2});
  s.instances.push_back(in);
  const Vec3f n = normalize(Vec3f{kTilted.x, kTilted.y, kTilted.z / 2.0f});
  expect_radiance(s, n.z, "instance under scale(1, 1, 2)");
}

// A roof whose two slopes (both 30 degrees) are single triangles along the ridge x = 0, the right one three times
// as wide as the left, so three times its area: each ridge vertex's normal is the area-weighted average
// (A_L n_L + 3 A_L n_R) / |...|, leaning 16.1 degrees right, where an unweighted average would point straight up and
// the geometric normal leans 30 degrees left. The camera sees x slightly left of the ridge, where the shading normal
// is almost the ridge vertices' one. Why unequal areas: with equal-area faces, area weighting and an unweighted
// average give the same normals, and the test could not tell them apart.
TEST(ShadingNormals, SmoothMeshGetsAreaWeightedVertexNormals) {
  SceneDesc s = floor_scene();
  const double slope = kPi / 6;
  const float run_left = 1.0f, run_right = 3.0f, tan_slope = float(std::tan(slope));
  MeshDesc roof;
  roof.name = "roof";
  roof.positions = {{0, -5, 0}, {0, 5, 0}, {-run_left, 0, -run_left * tan_slope}, {run_right, 0, -run_right * tan_slope}};
  roof.indices = {0, 1, 2, 1, 0, 3};  // both faces up
  roof.material = 0;
  roof.smooth = true;
  s.meshes.push_back(roof);
  const double x = -0.01;
  s.cameras[0].position = {float(x), -3.0f, 3.0f};
  s.cameras[0].gaze = normalize(Vec3f{0.0f, 3.0f, -3.0f});
  s.point_lights[0].position = {float(x), 0.0f, kLightHeight};
  const Vec3f n_left{float(-std::sin(slope)), 0.0f, float(std::cos(slope))};
  const Vec3f n_right{float(std::sin(slope)), 0.0f, float(std::cos(slope))};
  const float area_ratio = run_right / run_left;  // equal lengths along the ridge, equal slopes
  const auto shading_cos = [&](Vec3f ridge) {
    // The seen point (x, 0) has barycentric weight -x / run_left on the left eave vertex, the rest split evenly
    // between the two ridge vertices, whose normals are equal.
    const float t = float(-x) / run_left;
    return double(normalize(ridge * (1.0f - t) + n_left * t).z);
  };
  const double cos_weighted = shading_cos(normalize(n_left + n_right * area_ratio));
  const double cos_unweighted = shading_cos(normalize(n_left + n_right));
  const double d = kLightHeight - x * std::tan(slope);  // the point lies -x tan(slope) below the ridge
  const auto radiance = [&](double cos_shading) { return kAlbedo / kPi * kIntensity / (d * d) * cos_shading; };
  const auto w = build_world(s, {});
  PathSettings kiln;
  kiln.max_depth = 1;
  kiln.russian_roulette = false;
  const Estimate e = estimate_mean(*w, kiln, s.cameras[0], 2000);
  EXPECT_NEAR(e.mean, radiance(cos_weighted), 1e-3 * radiance(cos_weighted))
      << "unweighted vertex normals would give " << radiance(cos_unweighted) << ", the geometric normal "
      << radiance(std::cos(slope));
}

}  // namespace
}  // namespace kiln::test
