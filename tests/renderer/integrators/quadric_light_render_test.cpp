// pbrt quadrics as area lights in Kiln's path tracer: a Lambertian floor of albedo a seen at the origin has radiance
// a/pi * E, with E in closed form for a disk above it (on its axis), an annulus sector, the inside of a half cylinder
// standing on it and of a quarter sphere over it. NEE alone, BSDF sampling alone (emission found by bounce rays, so
// through the accelerators' quadric intersection and the oriented normal) and MIS all reach it.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "renderer/test_scenes.h"

namespace kiln::test {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kAlbedo = 0.5f;
constexpr float kL = 2.0f;
constexpr double kMaxZ = 5.0;

QuadricDesc emitter(QuadricType type, float r, float inner, float z0, float z1, float phi, Transform xf, bool flip) {
  QuadricDesc q;
  q.name = "quadric light";
  q.quadric = *make_quadric(type, r, inner, 0.0f, z0, z1, phi).quadric;
  q.to_world = xf;
  q.flip = flip;
  q.emission = Rgb(kL);
  return q;
}

double disk_irradiance(double r, double h) { return kPiD * kL * r * r / (h * h + r * r); }

struct Case {
  const char* name;
  QuadricDesc light;
  double irradiance;
};

std::vector<Case> cases() {
  const Transform down = Transform::rotate(90.0f, {1, 0, 0});  // object +z -> world -y
  const Transform up = Transform::rotate(-90.0f, {1, 0, 0});   // object +z -> world +y; object +y -> world -z
  constexpr float kH = 1.5f;
  return {
      {"disk", emitter(QuadricType::Disk, 0.8f, 0, 0, 0, 360, Transform::translate({0, kH, 0}) * down, false),
       disk_irradiance(0.8, kH)},
      // pbrt's feature scenes light a floor with a ReverseOrientation'd disk facing down: the same, flipped twice.
      {"reversed disk", emitter(QuadricType::Disk, 0.8f, 0, 0, 0, 360, Transform::translate({0, kH, 0}) * up, true),
       disk_irradiance(0.8, kH)},
      {"annulus sector",
       emitter(QuadricType::Disk, 0.8f, 0.3f, 0, 0, 90, Transform::translate({0, kH, 0}) * down, false),
       0.25 * (disk_irradiance(0.8, kH) - disk_irradiance(0.3, kH))},
      // Half a cylinder behind the origin (object phi in [0, pi] is world z <= 0), open towards the camera, its
      // inside emitting: 1/2 pi L H^2 / (H^2 + R^2).
      {"half cylinder", emitter(QuadricType::Cylinder, 0.6f, 0, 0.0f, 1.2f, 180, up, true),
       0.5 * kPiD * kL * 1.44 / (1.44 + 0.36)},
      // A quarter sphere (dome half) behind the origin: half the sky, 1/2 pi L.
      {"quarter sphere", emitter(QuadricType::Sphere, 1.0f, 0, 0.0f, 1.0f, 180, up, true), 0.5 * kPiD * kL},
  };
}

TEST(QuadricLights, LambertianFloorMatchesTheClosedFormUnderEveryStrategy) {
  for (const Case& c : cases()) {
    SceneDesc s = lit_floor_scene(kAlbedo);
    s.quadrics.push_back(c.light);
    const auto w = build_world(s, {});
    ASSERT_TRUE(w->features & kFeatureQuadricLights);
    ASSERT_EQ(w->stats.quadric_lights, 1u);
    const double want = kAlbedo / kPiD * c.irradiance;
    for (const char* strategy : {"nee", "brdf", "mis"}) {
      PathSettings p = kiln_strategy(strategy, PathSettings{}, "test");
      p.max_depth = 1;
      p.russian_roulette = false;
      const Estimate e = estimate_mean(*w, p, s.cameras[0], 40000);
      EXPECT_NEAR(e.mean, want, kMaxZ * e.stderr_) << c.name << ", " << strategy << ": " << e.mean << " +- "
                                                   << e.stderr_ << " vs " << want;
      EXPECT_GT(e.stderr_, 0.0);
    }
  }
}

}  // namespace
}  // namespace kiln::test
