// Rays from inside closed surfaces never escape, with either accelerator.
#include <gtest/gtest.h>

#include "accel_test_util.h"
#include "renderer/accel/accelerator.h"

namespace kiln {
namespace {

using namespace kiln::test;

constexpr double kMaxEscapeRate = 2e-5;
constexpr size_t kRays = 50000;
const Vec3f kFarCentre(148376.0f, 1234.0f, -223423.0f);

// Origins inside the radius-r ball around centre (some a hair from the surface); directions uniform or aimed
// exactly at edge points and (with vertices) vertices of mesh, the places where a non-watertight test leaks.
size_t count_escapes(const Accelerator& acc, Vec3f centre, float r, const TriangleMesh* mesh, bool vertices,
                     uint64_t seed) {
  Rng rng(seed, 3);
  size_t escapes = 0;
  for (size_t i = 0; i < kRays; ++i) {
    const float depth = (i % 4 == 0) ? 1e-4f : rng.next_float();
    const Vec3f o = centre + random_direction(rng) * (r * (1.0f - depth) * 0.98f);
    Vec3f d = random_direction(rng);
    if (mesh && i % 3 != 0) {
      const size_t tri = std::min(size_t(rng.next_float() * float(mesh->triangle_count())), mesh->triangle_count() - 1);
      const Vec3f a = mesh->vertex(tri, 0), b = mesh->vertex(tri, int(i % 2) + 1);
      d = (i % 3 == 1 && vertices ? a : a + (b - a) * rng.next_float()) - o;
    }
    Hit h;
    if (!acc.intersect(Ray{o, d}, h) || !acc.occluded(Ray{o, d})) ++escapes;
  }
  return escapes;
}

// Embree 3.13's triangle test (even with RTC_SCENE_FLAG_ROBUST) is watertight along edges but not at vertices:
// about 0.4% of rays aimed exactly at an icosphere's vertices slip through. The BVH's Woop-Benthin-Wald test does
// not leak there either, so only the BVH is held to vertex-aimed rays.
void expect_closed(const WorldGeometry& g, Vec3f centre, float r, const TriangleMesh* mesh, const char* what) {
  for (AccelKind k : {AccelKind::Embree, AccelKind::Bvh}) {
    const auto acc = make_accelerator(k, g);
    const size_t escapes = count_escapes(*acc, centre, r, mesh, k == AccelKind::Bvh, 17);
    EXPECT_LE(double(escapes), kMaxEscapeRate * double(kRays))
        << what << " (" << acc->stats().name << "): " << escapes << " of " << kRays << " rays escaped";
  }
}

TEST(AccelWatertight, RaysInsideAClosedMeshNeverEscape) {
  WorldGeometry g;
  add_mesh(g, make_icosphere(4, Vec3f(0.1f, 0.2f, -0.3f), 1.0f));
  // The icosphere's faces are inside the sphere of its vertices: origins stay within the inscribed radius.
  expect_closed(g, Vec3f(0.1f, 0.2f, -0.3f), 0.99f, &g.meshes[0], "icosphere");
}

TEST(AccelWatertight, RaysInsideAFarClosedMeshNeverEscape) {
  WorldGeometry g;
  add_mesh(g, make_icosphere(3, kFarCentre, 3.0f));
  expect_closed(g, kFarCentre, 3.0f * 0.98f, &g.meshes[0], "far icosphere");
}

TEST(AccelWatertight, RaysInsideAnInstancedClosedMeshNeverEscape) {
  WorldGeometry g;
  const uint32_t proto = add_prototype(g, make_icosphere(3));
  const Transform xf = Transform::translate(Vec3f(5, -2, 1)) * Transform::rotate(40, Vec3f(1, 0, 1)) *
                       Transform::scale(Vec3f(2.0f, 2.0f, -2.0f));
  add_instance(g, proto, xf);
  TriangleMesh world = g.prototypes[proto];  // the same mesh in world space, for aiming at its vertices
  for (Vec3f& p : world.p) p = xf.point(p);
  expect_closed(g, Vec3f(5, -2, 1), 2.0f * 0.98f, &world, "instanced icosphere");
}

TEST(AccelWatertight, RaysInsideSpheresNeverEscape) {
  {
    WorldGeometry g;
    add_sphere(g, Vec3f(0.5f, 0, 0), 2.0f);
    expect_closed(g, Vec3f(0.5f, 0, 0), 2.0f, nullptr, "sphere");
  }
  {
    WorldGeometry g;
    add_sphere(g, kFarCentre, 0.5f);
    expect_closed(g, kFarCentre, 0.5f, nullptr, "far sphere");
  }
  {
    WorldGeometry g;  // an ellipsoid with semi-axes 3, 1, 2: origins within its inscribed unit sphere
    add_sphere(g, Vec3f(0, 0, 0), 1.0f,
               Transform::translate(Vec3f(1, 2, 3)) * Transform::rotate(25, Vec3f(0, 1, 1)) *
                   Transform::scale(Vec3f(3.0f, 1.0f, 2.0f)));
    expect_closed(g, Vec3f(1, 2, 3), 1.0f, nullptr, "ellipsoid");
  }
}

}  // namespace
}  // namespace kiln
