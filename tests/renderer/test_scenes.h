// Scenes the renderer tests measure closed forms in, shared by the light, quadric-light, alpha and environment-map
// tests: a lit Lambertian floor seen at one point, a ball in front of a camera, and the irradiance of a rectangle.
#pragma once
#include <cmath>
#include <string>

#include "renderer/render_util.h"

namespace kiln::test {

// A square pinhole camera at `position` looking along `gaze` with a vertical field of view of fov_deg.
inline CameraDesc pinhole(Vec3f position, Vec3f gaze, Vec3f up, float fov_deg, int size) {
  CameraDesc cam;
  cam.id = "1";
  cam.position = position;
  cam.gaze = normalize(gaze);
  cam.up = up;
  cam.use_fov = true;
  cam.fov_y_deg = fov_deg;
  cam.width = cam.height = size;
  return cam;
}

// A large Lambertian floor (y = 0, normal +y) of the given albedo (material 0), seen at the origin by a narrow camera
// from the side: its radiance there is albedo / pi * E, E the irradiance at the origin. 45 degrees above the floor,
// the pixels' footprint (5 mm) leaves the irradiance's curvature below 1e-5 relative.
inline SceneDesc lit_floor_scene(float albedo, const std::string& source_path = "") {
  SceneDesc s = lambertian_scene(albedo, source_path);
  MeshDesc floor;
  floor.name = "floor";
  floor.positions = {{-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}};
  floor.indices = {0, 1, 2, 0, 2, 3};  // (v1-v0)x(v2-v0) = +y
  floor.material = 0;
  s.meshes.push_back(floor);
  s.cameras.push_back(pinhole({0.0f, 3.0f, 3.0f}, {0.0f, -3.0f, -3.0f}, {0, 1, 0}, 0.05f, 4));
  return s;
}

// lit_floor_scene's radiance at the origin (camera cam of world w) under NEE, BSDF sampling and MIS, one bounce and no
// roulette, each within max_z standard errors of want (albedo / pi x the irradiance there), over n samples.
inline void expect_floor_radiance_under_strategies(const World& w, const CameraDesc& cam, double want, uint32_t n,
                                                   double max_z, const std::string& what) {
  for (const char* strategy : {"nee", "brdf", "mis"}) {
    PathSettings p = kiln_strategy(strategy, PathSettings{}, "test");
    p.max_depth = 1;
    p.russian_roulette = false;
    const Estimate e = estimate_mean(w, p, cam, n);
    EXPECT_NEAR(e.mean, want, max_z * e.stderr_)
        << what << ", " << strategy << ": " << e.mean << " +- " << e.stderr_ << " vs " << want;
    EXPECT_GT(e.stderr_, 0.0) << what << ", " << strategy;
  }
}

// A Lambertian ball of the given albedo (material 0, radius 1 at the origin) filling the view of an 8 x 8 camera.
inline SceneDesc ball_scene(float albedo, const std::string& source_path) {
  SceneDesc s = lambertian_scene(albedo, source_path);
  SphereDesc ball;
  ball.name = "ball";
  ball.radius = 1.0f;
  ball.material = 0;
  s.spheres.push_back(ball);
  s.cameras.push_back(pinhole({0, 0, 3}, {0, 0, -1}, {0, 1, 0}, 20.0f, 8));
  return s;
}

// Irradiance at a point from a parallel Lambertian rectangle a x b of radiance L at height h with its corner straight
// above the point (differential-area-to-rectangle form factor, Howell's catalogue C-11) times pi L.
inline double corner_rectangle_irradiance(double radiance, double a, double b, double h) {
  constexpr double kPiD = 3.14159265358979323846;
  const double x = a / h, y = b / h;
  const double f = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                    y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                   (2 * kPiD);
  return kPiD * radiance * f;
}

}  // namespace kiln::test
