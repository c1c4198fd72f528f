// Motion blur: the image of a shape moving by d over the shutter is its coverage averaged over time, which is known
// in closed form for a sphere and a quad seen by a pinhole camera (the fraction of [0, 1] during which a pixel's ray
// meets the moved shape, averaged over the pixel). Checked for a sphere, a world mesh and a mesh instance, with
// Embree and with the in-house BVH; the render is bit-identical for any thread count and tile order.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "renderer/render_util.h"

namespace kiln::test {
namespace {

constexpr float kDepth = 10.0f;      // distance of the shapes from the camera, along -z
constexpr float kRadius = 0.3f;      // sphere radius; quads are 2 kRadius wide
constexpr float kStartX = -0.8f;     // centre at time 0
constexpr Vec3f kMotion{1.2f, 0, 0};  // the smear: 4 diameters to the right
constexpr int kWidth = 64, kHeight = 4;
constexpr uint32_t kSpp = 1024;
constexpr int kQuadrature = 24;      // per pixel axis for the analytic pixel average

enum class Kind { Sphere, Mesh, Instance };

// Only ambient light and no background: a pixel's value is ka * Ia (= 1) times the fraction of its samples whose
// ray meets the shape, under the course ray tracer (one ray per sample).
SceneDesc moving_scene(Kind kind, Vec3f motion) {
  SceneDesc s;
  s.source_path = "motion.test";
  s.rules = SceneRules::Ceng795Course;
  s.ambient_light = Rgb(1.0f);
  MaterialDesc m;
  m.ambient = Rgb(1.0f);
  s.materials.push_back(m);
  const Vec3f c(kStartX, 0, -kDepth);
  if (kind == Kind::Sphere) {
    SphereDesc sph;
    sph.name = "ball";
    sph.center = c;
    sph.radius = kRadius;
    sph.material = 0;
    sph.motion = motion;
    s.spheres.push_back(sph);
  } else {
    MeshDesc quad;
    quad.name = "quad";
    // Facing the camera ((v1-v0)x(v2-v0) along +z), so backface culling keeps it.
    quad.positions = {{-kRadius, -kRadius, 0}, {kRadius, -kRadius, 0}, {kRadius, kRadius, 0}, {-kRadius, kRadius, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    quad.material = 0;
    if (kind == Kind::Mesh) {
      quad.to_world = Transform::translate(c);
      quad.motion = motion;
    } else {
      quad.is_instance_base = true;
      quad.visible = false;
      InstanceDesc inst;
      inst.name = "quad instance";
      inst.base_mesh = 0;
      inst.material = 0;
      inst.to_world = Transform::translate(c);
      inst.motion = motion;
      s.instances.push_back(inst);
    }
    s.meshes.push_back(quad);
  }
  CameraDesc cam;
  cam.id = "1";
  cam.gaze = {0, 0, -1};
  cam.use_fov = true;
  cam.fov_y_deg = 2.0f;
  cam.width = kWidth;
  cam.height = kHeight;
  s.cameras.push_back(cam);
  return s;
}

// Length of {t in [0, 1] : lo <= t <= hi}.
double overlap(double lo, double hi) { return std::max(0.0, std::min(hi, 1.0) - std::max(lo, 0.0)); }

// Fraction of the shutter during which the ray (origin o, direction d) meets the shape.
double ray_coverage(Kind kind, Vec3f o, Vec3f d, Vec3f motion) {
  const double c0[3] = {kStartX - o.x, -o.y, -kDepth - o.z};
  if (kind == Kind::Sphere) {
    // |(c0 + t m) x u|^2 <= R^2 |u|^2: a quadratic a t^2 + b t + c <= 0 in t.
    const double u[3] = {d.x, d.y, d.z}, m[3] = {motion.x, motion.y, motion.z};
    auto cross = [](const double* a, const double* b, double* r) {
      r[0] = a[1] * b[2] - a[2] * b[1];
      r[1] = a[2] * b[0] - a[0] * b[2];
      r[2] = a[0] * b[1] - a[1] * b[0];
    };
    double p[3], q[3];
    cross(c0, u, p);
    cross(m, u, q);
    const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    const double a = q[0] * q[0] + q[1] * q[1] + q[2] * q[2], b = 2 * (p[0] * q[0] + p[1] * q[1] + p[2] * q[2]),
                 c = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - double(kRadius) * kRadius * uu;
    const double disc = b * b - 4 * a * c;
    if (disc <= 0) return 0;
    return overlap((-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a));
  }
  // The quad's plane z = -kDepth: the ray crosses it at x, y; the quad covers x while x - m t is in its span.
  const double s = c0[2] / d.z, x = d.x * s, y = d.y * s;
  if (std::abs(y) > kRadius) return 0;
  return overlap((x - c0[0] - kRadius) / motion.x, (x - c0[0] + kRadius) / motion.x);
}

// The pixel's expected value: coverage averaged over the pixel (box filter) by a midpoint quadrature.
double pixel_coverage(Kind kind, const Camera& cam, int px, int py, Vec3f motion) {
  double sum = 0;
  for (int i = 0; i < kQuadrature; ++i)
    for (int j = 0; j < kQuadrature; ++j) {
      const Ray r = cam.generate_ray(float(px) + (float(i) + 0.5f) / kQuadrature,
                                     float(py) + (float(j) + 0.5f) / kQuadrature, Vec2f{0.5f, 0.5f});
      sum += ray_coverage(kind, r.o, r.d, motion);
    }
  return sum / (kQuadrature * kQuadrature);
}

std::unique_ptr<World> world_for(const SceneDesc& s, AccelKind accel) {
  WorldOptions wo;
  wo.accel = accel;
  return build_world(s, wo);
}

// Pixels agree with the analytic profile within 5 binomial standard errors, and the smear's width (pixels more than
// 2% covered) is the analytic one.
void expect_analytic_smear(Kind kind, AccelKind accel, const char* what) {
  SCOPED_TRACE(what);
  const SceneDesc s = moving_scene(kind, kMotion);
  const auto w = world_for(s, accel);
  ASSERT_TRUE(w->features & kFeatureMotionBlur);
  const IntegratorSettings settings = scene_settings(s.cameras[0], s, w->features);
  const Image img = render_image(*w, s.cameras[0], settings, kSpp, 17);
  const Camera cam(s.cameras[0]);
  int width = 0, expected_width = 0, partial = 0;
  for (int y = 1; y < 3; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double c = pixel_coverage(kind, cam, x, y, kMotion);
      const double v = img.at(x, y).g;
      const double se = std::sqrt(std::max(c * (1 - c), 1.0 / kSpp) / kSpp);
      EXPECT_NEAR(v, c, 5 * se + 2e-3) << "pixel " << x << "," << y;
      width += v > 0.02;
      expected_width += c > 0.02;
      partial += c > 0.05 && c < 0.95;
    }
  EXPECT_EQ(width, expected_width);
  EXPECT_GT(partial, 20) << "the smear spans many partly covered pixels";
}

TEST(MotionBlur, SphereSmearMatchesTheAnalyticCoverage) {
  expect_analytic_smear(Kind::Sphere, AccelKind::Embree, "embree");
  expect_analytic_smear(Kind::Sphere, AccelKind::Bvh, "bvh");
}

TEST(MotionBlur, MeshSmearMatchesTheAnalyticCoverage) {
  expect_analytic_smear(Kind::Mesh, AccelKind::Embree, "embree");
  expect_analytic_smear(Kind::Mesh, AccelKind::Bvh, "bvh");
}

TEST(MotionBlur, InstanceSmearMatchesTheAnalyticCoverage) {
  expect_analytic_smear(Kind::Instance, AccelKind::Embree, "embree");
  expect_analytic_smear(Kind::Instance, AccelKind::Bvh, "bvh");
}

// ---- Kiln's path tracer: the camera sample's time must reach every ray of the path ----------------------------------

// Fraction of the shutter during which the line o + s u meets the sphere of radius kRadius centred at c0 + t motion
// (|(c0 + t m - o) x u|^2 <= R^2 |u|^2, a quadratic in t).
double line_coverage(Vec3f o, Vec3f u, Vec3f c0, Vec3f motion) {
  const Vec3f p = cross(c0 - o, u), q = cross(motion, u);
  const double a = dot(q, q), b = 2.0 * dot(p, q), c = dot(p, p) - double(kRadius) * kRadius * dot(u, u);
  const double disc = b * b - 4 * a * c;
  if (disc <= 0) return 0;
  return overlap((-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a));
}

constexpr float kMirrorDepth = kDepth / 4;  // a mirror facing the camera at z = -kMirrorDepth
constexpr Vec3f kLight{0, 3, -kDepth + 3};  // the point light over the floor
constexpr Vec3f kOccluderStart{kStartX, 1.5f, -kDepth + 1.5f};  // halfway between the floor's centre and the light
constexpr float kFloorAlbedo = 0.5f;
constexpr Rgb kLightIntensity{40.0f};

// A unit-facing quad z = z0 of half-size h facing +z, with material m.
MeshDesc facing_quad(const std::string& name, float z0, float h, int m) {
  MeshDesc q;
  q.name = name;
  q.positions = {{-h, -h, z0}, {h, -h, z0}, {h, h, z0}, {-h, h, z0}};
  q.indices = {0, 1, 2, 0, 2, 3};
  q.material = m;
  return q;
}

// Materials: 0 the floor's Lambertian, 1 black, 2 a perfect mirror. Emitters do not move (README, motion blur), so
// the moving ball is always a black occluder.
SceneDesc kiln_motion_scene(bool mirror) {
  SceneDesc s = lambertian_scene(kFloorAlbedo, "motion_pt.test");
  s.rules = SceneRules::Kiln;
  s.cameras.push_back(moving_scene(Kind::Sphere, kMotion).cameras[0]);
  MaterialDesc black;
  black.brdf = 0;
  s.materials.push_back(black);
  SphereDesc ball;
  ball.name = "occluder";
  ball.radius = kRadius;
  ball.motion = kMotion;
  ball.material = 1;
  if (mirror) {
    // A mirror facing the camera, a white sky (a constant infinite light) behind the camera, and the ball between
    // them, where its mirror image is the ball of moving_scene: the image is 1 minus the analytic coverage, found by
    // bounce rays only.
    MaterialDesc m;
    m.type = MaterialType::Mirror;
    m.mirror = Rgb(1.0f);
    s.materials.push_back(m);
    s.meshes.push_back(facing_quad("mirror", -kMirrorDepth, 5, 2));
    s.infinite_lights.push_back({Rgb(1.0f)});
    ball.center = Vec3f(kStartX, 0, -2 * kMirrorDepth + kDepth);
  } else {
    // A floor lit by a point light; the ball, out of the camera's view, casts a moving shadow onto it.
    s.meshes.push_back(facing_quad("floor", -kDepth, 20, 0));
    s.point_lights.push_back({kLight, kLightIntensity});
    ball.center = kOccluderStart;
  }
  s.spheres.push_back(ball);
  return s;
}

// A pixel's expected value, and what it would be if the moving ball did not cover it (the binomial error's scale).
struct Expected {
  double value = 0, uncovered = 0;
};

// The floor's radiance toward the camera, albedo / pi * I cos / d^2, times the light's visibility averaged over the
// shutter, averaged over the pixel (box filter) by a midpoint quadrature.
Expected shadowed_floor(const Camera& cam, int px, int py) {
  Expected e;
  for (int i = 0; i < kQuadrature; ++i)
    for (int j = 0; j < kQuadrature; ++j) {
      const Ray r = cam.generate_ray(float(px) + (float(i) + 0.5f) / kQuadrature,
                                     float(py) + (float(j) + 0.5f) / kQuadrature, Vec2f{0.5f, 0.5f});
      const Vec3f p = r.o + r.d * ((-kDepth - r.o.z) / r.d.z);
      const Vec3f to_light = kLight - p;
      const double d2 = dot(to_light, to_light), cos_floor = to_light.z / std::sqrt(d2);
      const double lit = kFloorAlbedo / kPi * kLightIntensity.g * cos_floor / d2;
      e.value += lit * (1.0 - line_coverage(p, to_light, kOccluderStart, kMotion));
      e.uncovered += lit;
    }
  e.value /= kQuadrature * kQuadrature;
  e.uncovered /= kQuadrature * kQuadrature;
  return e;
}

// Pixels against the expectation within 5 standard errors of a sample that is either 0 or the pixel's uncovered
// value (binomial), and enough partly covered pixels to show a smear.
void expect_smear_under_kiln(const SceneDesc& s, const std::function<Expected(const Camera&, int, int)>& expected) {
  const auto w = build_world(s, {});
  ASSERT_TRUE(w->features & kFeatureMotionBlur);
  const IntegratorSettings settings = scene_settings(s.cameras[0], s, w->features);
  ASSERT_NE(settings.describe().find("Kiln path tracer"), std::string::npos) << settings.describe();
  const Image img = render_image(*w, s.cameras[0], settings, kSpp, 23);
  const Camera cam(s.cameras[0]);
  int partial = 0;
  for (int y = 1; y < 3; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const Expected e = expected(cam, x, y);
      const double c = e.value / e.uncovered;
      const double se = e.uncovered * std::sqrt(std::max(c * (1 - c), 1.0 / kSpp) / kSpp);
      EXPECT_NEAR(img.at(x, y).g, e.value, 5 * se + 2e-3 * e.uncovered) << "pixel " << x << "," << y;
      partial += c > 0.05 && c < 0.95;
    }
  EXPECT_GT(partial, 20) << "the smear spans many partly covered pixels";
}

// A bounce ray (here off a mirror) keeps the camera sample's time: the moving ball seen in the mirror against the sky
// is the analytic smear. A bounce ray at time 0 would show it sharp, where it stands at the shutter's opening.
TEST(MotionBlur, KilnPathTracerBounceRaysKeepTheSampleTime) {
  expect_smear_under_kiln(kiln_motion_scene(true), [](const Camera& cam, int x, int y) {
    return Expected{1.0 - pixel_coverage(Kind::Sphere, cam, x, y, kMotion), 1.0};
  });
}

// A shadow ray of next event estimation keeps the camera sample's time: a ball moving between a point light and a
// floor casts the time-averaged shadow. A shadow ray at time 0 would cast it sharp.
TEST(MotionBlur, KilnPathTracerShadowRaysKeepTheSampleTime) {
  expect_smear_under_kiln(kiln_motion_scene(false), shadowed_floor);
}

bool bit_identical(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Rgb)) == 0;
}

TEST(MotionBlur, DeterministicForAnyThreadCountAndTileOrder) {
  const SceneDesc s = moving_scene(Kind::Sphere, kMotion);
  const auto w = build_world(s, {});
  const IntegratorSettings settings = scene_settings(s.cameras[0], s, w->features);
  const Image one = render_image(*w, s.cameras[0], settings, 16, 3, 1);
  const Image two = render_image(*w, s.cameras[0], settings, 16, 3, 2);
  const Image reversed = render_image(*w, s.cameras[0], settings, 16, 3, 2, true);
  EXPECT_TRUE(bit_identical(one, two));
  EXPECT_TRUE(bit_identical(one, reversed));
  EXPECT_FALSE(bit_identical(one, render_image(*w, s.cameras[0], settings, 16, 4, 2)));
}

TEST(MotionBlur, AStillSceneTakesNoTimeSample) {
  const SceneDesc still = moving_scene(Kind::Sphere, Vec3f(0.0f));
  const auto w = build_world(still, {});
  EXPECT_FALSE(w->features & kFeatureMotionBlur);
  EXPECT_FALSE(w->geometry.has_motion);
  EXPECT_EQ(w->stats.moving_shapes, 0u);
  const auto moving = build_world(moving_scene(Kind::Sphere, kMotion), {});
  EXPECT_EQ(moving->stats.moving_shapes, 1u);
}

}  // namespace
}  // namespace kiln::test
