// pbrt-v4 scenes through the whole renderer (tests/data/pbrt/, whose comments derive the answers): camera rays
// through given pixels hit known points (LookAt with pbrt's left-handed image, Rotate), ObjectInstance copies sit
// where their transforms put them, and pbrt's unit furnace (box and subdivided sphere) gives 1 - a^(D+1) for
// maxdepth D, which pins Integrator "maxdepth" to Kiln's bounce count.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "renderer/render_util.h"
#include "renderer/world/ray_query.h"

namespace kiln::test {
namespace {

const std::string kData = std::string(KILN_SOURCE_DIR) + "/tests/data/pbrt/";

struct Loaded {
  SceneDesc desc;
  std::unique_ptr<World> world;
};

Loaded load(const std::string& name) {
  Loaded l;
  l.desc = load_scene(kData + name);
  l.world = build_world(l.desc, {});
  return l;
}

std::optional<Vec3f> first_hit(const World& w, const Ray& ray) {
  Hit hit;
  RayCounters c;
  if (!query_intersect(w, ray, hit, c, true)) return std::nullopt;
  return ray.o + ray.d * hit.t;
}

std::optional<Vec3f> hit_through_pixel(const Loaded& l, float x, float y) {
  const Camera cam(l.desc.cameras.at(0));
  return first_hit(*l.world, cam.generate_ray(x, y, {0.5f, 0.5f}));
}

void expect_point(std::optional<Vec3f> p, Vec3f expected, float tol = 1e-4f) {
  ASSERT_TRUE(p) << "no hit; expected (" << expected.x << ", " << expected.y << ", " << expected.z << ")";
  EXPECT_NEAR(p->x, expected.x, tol);
  EXPECT_NEAR(p->y, expected.y, tol);
  EXPECT_NEAR(p->z, expected.z, tol);
}

TEST(PbrtScene, LookAtRayHitsTheKnownPointOnTheLeftOfTheImage) {
  const Loaded l = load("lookat_hit.pbrt");
  expect_point(hit_through_pixel(l, 25.5f, 40.5f), {2.45f, 0.95f, 0.0f});
  // The mirror-image pixel would hit world x = -2.45: nothing there (a right-handed camera would hit the quad here).
  EXPECT_FALSE(hit_through_pixel(l, 74.5f, 40.5f));
}

TEST(PbrtScene, RotateMovesTheTriangleToTheKnownHitPoint) {
  const Loaded l = load("rotate_hit.pbrt");
  expect_point(hit_through_pixel(l, 50.5f, 30.5f), {-0.05f, 1.95f, 0.0f});
  // A rotation the other way would have put it at y = -2: the pixel looking at (-0.05, -1.95, 0) sees nothing.
  EXPECT_FALSE(hit_through_pixel(l, 50.5f, 69.5f));
}

TEST(PbrtScene, ObjectInstancesSitWhereTheirTransformsPutThem) {
  const Loaded l = load("instancing.pbrt");
  EXPECT_EQ(l.world->stats.instances, 3u);
  const Vec3f eye = l.desc.cameras[0].position;
  auto towards = [&](Vec3f target) { return first_hit(*l.world, Ray{eye, normalize(target - eye), 0.0f, kInfinity}); };
  // Triangles (definition: z = -1; the scaled instance: z = -2), off-centre so that the spheres do not hide them.
  for (const Vec3f target : {Vec3f{-2.8f, -0.3f, -1}, Vec3f{0.2f, -0.3f, -1}, Vec3f{3.6f, -0.7f, -2}})
    expect_point(towards(target), target);
  // Spheres: radius 0.25 at x = -3 and 0, radius 0.5 at x = 3; aim at each sphere's point nearest the eye.
  for (const auto& [centre, radius] :
       {std::pair{Vec3f{-3, 0, 0}, 0.25f}, std::pair{Vec3f{0, 0, 0}, 0.25f}, std::pair{Vec3f{3, 0, 0}, 0.5f}}) {
    const Vec3f nearest = centre + normalize(eye - centre) * radius;
    expect_point(towards(nearest), nearest, 1e-3f);
  }
  // Where the definition itself lies untransformed but scaled copies do not reach: empty.
  EXPECT_FALSE(towards({1.6f, -0.3f, -1}));
}

// pbrt's unit furnace: emission 1 - a, albedo a, maxdepth D: radiance 1 - a^(D+1). The identity needs every bounce
// to keep a of the energy, which shading normals break (a direction sampled about the smooth normal can point
// into the surface and is lost), so the loop-subdivided sphere is shaded flat here.
void expect_furnace(const std::string& file, double albedo, int depth) {
  Loaded l;
  l.desc = load_scene(kData + file);
  for (MeshDesc& m : l.desc.meshes) {
    m.smooth = false;
    m.normals.clear();
  }
  l.world = build_world(l.desc, {});
  ASSERT_EQ(*l.desc.max_recursion_depth, depth);
  const IntegratorSettings s = scene_settings(l.desc.cameras[0], l.desc, l.world->features);
  ASSERT_TRUE(std::holds_alternative<PathSettings>(s.method));  // pbrt scenes render with Kiln's rules
  EXPECT_EQ(std::get<PathSettings>(s.method).max_depth, depth);
  const Estimate e = estimate_mean(*l.world, s, l.desc.cameras[0], 200000);
  const double expected = 1.0 - std::pow(albedo, depth + 1);
  EXPECT_NEAR(e.mean, expected, 4.5 * e.stderr_ + 1e-4) << file << ": " << e.mean << " +- " << e.stderr_;
  // One bounce fewer must be distinguishable, or the test could not catch a depth off by one.
  EXPECT_GT(std::abs(e.mean - (1.0 - std::pow(albedo, depth))), 4.5 * e.stderr_) << file;
}

TEST(PbrtScene, UnitFurnaceInsideABoxMatchesMaxDepth) { expect_furnace("furnace_box.pbrt", 0.5, 5); }

TEST(PbrtScene, UnitFurnaceInsideASubdividedSphereMatchesMaxDepth) { expect_furnace("furnace_sphere.pbrt", 0.6, 5); }

}  // namespace
}  // namespace kiln::test
