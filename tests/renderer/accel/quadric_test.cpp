// Quadrics (pbrt disks, cylinders, partial spheres) in both accelerators: hit points and surface coordinates against
// their closed forms (a cut-away near side lets the ray find the far one), Embree and the BVH agree ray by ray on
// placed, stretched, moving and animated quadrics (check-bvh), and the hit's normal is the oriented one (flip).
#include <gtest/gtest.h>

#include "accel_test_util.h"
#include "renderer/accel/bvh.h"
#include "renderer/accel/check_bvh.h"
#include "renderer/accel/embree_accel.h"
#include "renderer/accel/quadric_intersect.h"
#include "renderer/accel/surface_point.h"

namespace kiln {
namespace {

using namespace kiln::test;

constexpr float kRel = 2e-6f;  // hit distances agree with the closed form to a few float ulps

Quadric quadric(QuadricType type, float r, float inner, float height, float z0, float z1, float phi_deg) {
  return *make_quadric(type, r, inner, height, z0, z1, phi_deg).quadric;
}

TEST(QuadricIntersect, DiskAnnulusAndSectorHitsMatchTheirClosedForms) {
  const Quadric q = quadric(QuadricType::Disk, 2.0f, 0.5f, 0.75f, 0, 0, 270.0f);
  // Straight down onto (x, y): t = 10 - 0.75, u = phi / (3/2 pi), v = (2 - r) / 1.5.
  const auto hit = intersect_quadric(q, {1.0f, 1.0f, 10.0f}, {0, 0, -1}, 0.0f, kInfinity);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 9.25f, kRel * 9.25f);
  EXPECT_NEAR(hit->uv.x, (kPi / 4.0f) / (1.5f * kPi), 1e-6f);
  EXPECT_NEAR(hit->uv.y, (2.0f - std::sqrt(2.0f)) / 1.5f, 1e-6f);
  EXPECT_FALSE(intersect_quadric(q, {0.2f, 0.2f, 10.0f}, {0, 0, -1}, 0.0f, kInfinity));   // the hole
  EXPECT_FALSE(intersect_quadric(q, {1.0f, -1.0f, 10.0f}, {0, 0, -1}, 0.0f, kInfinity));  // phi = 315 > 270
  EXPECT_FALSE(intersect_quadric(q, {1.5f, 1.5f, 10.0f}, {0, 0, -1}, 0.0f, kInfinity));   // r = 2.12 > 2
  EXPECT_FALSE(intersect_quadric(q, {1.0f, 1.0f, 10.0f}, {1, 0, 0}, 0.0f, kInfinity));    // parallel
  EXPECT_FALSE(intersect_quadric(q, {1.0f, 1.0f, 10.0f}, {0, 0, -1}, 0.0f, 9.0f));        // beyond tmax
  // An oblique ray: t where it crosses z = 0.75.
  const Vec3f o(-3.0f, 0.4f, 2.0f), d = normalize(Vec3f(1.0f, 0.1f, -0.5f));
  const auto oblique = intersect_quadric(q, o, d, 0.0f, kInfinity);
  ASSERT_TRUE(oblique);
  EXPECT_NEAR(oblique->t, (0.75f - o.z) / d.z, kRel * oblique->t);
}

TEST(QuadricIntersect, CylinderNearSideAndCutAwayFarSide) {
  // Radius 1, z in [-1, 2], phi up to 180: the half with y >= 0.
  const Quadric q = quadric(QuadricType::Cylinder, 1.0f, 0, 0, -1.0f, 2.0f, 180.0f);
  // Along -y from y = 5 at x = 0.6: the near crossing at y = +0.8 (phi ~ 53 deg) is kept.
  const auto hit = intersect_quadric(q, {0.6f, 5.0f, 0.5f}, {0, -1, 0}, 0.0f, kInfinity);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4.2f, kRel * 4.2f);
  EXPECT_EQ(hit->root, 0u);
  EXPECT_NEAR(hit->uv.x, std::atan2(0.8f, 0.6f) / kPi, 1e-6f);
  EXPECT_NEAR(hit->uv.y, 0.5f, 1e-6f);
  // Along +y from y = -5: the near crossing (y = -0.8) is cut away, the far one (y = +0.8) is found from inside.
  const auto far = intersect_quadric(q, {0.6f, -5.0f, 0.5f}, {0, 1, 0}, 0.0f, kInfinity);
  ASSERT_TRUE(far);
  EXPECT_NEAR(far->t, 5.8f, kRel * 5.8f);
  EXPECT_EQ(far->root, 1u);
  // Above z_max, parallel to the axis, and outside the radius: nothing.
  EXPECT_FALSE(intersect_quadric(q, {0.6f, 5.0f, 2.5f}, {0, -1, 0}, 0.0f, kInfinity));
  EXPECT_FALSE(intersect_quadric(q, {0.6f, 0.8f, 5.0f}, {0, 0, -1}, 0.0f, kInfinity));
  EXPECT_FALSE(intersect_quadric(q, {1.2f, 5.0f, 0.5f}, {0, -1, 0}, 0.0f, kInfinity));
}

TEST(QuadricIntersect, PartialSphereZoneAndWedge) {
  // Radius 2, z in [-1, 1.5], phi up to 90 degrees.
  const Quadric q = quadric(QuadricType::Sphere, 2.0f, 0, 0, -1.0f, 1.5f, 90.0f);
  // From far along the diagonal x = y at z = 0.5: hits the sphere at |p| = 2.
  const Vec3f d = normalize(Vec3f(-1.0f, -1.0f, 0.0f));
  const Vec3f o = Vec3f(10.0f, 10.0f, 0.5f);
  const auto hit = intersect_quadric(q, o, d, 0.0f, kInfinity);
  ASSERT_TRUE(hit);
  const float ring = std::sqrt(4.0f - 0.25f);
  EXPECT_NEAR(hit->t, 10.0f * std::sqrt(2.0f) - ring, kRel * 14.2f);
  EXPECT_NEAR(hit->uv.x, 0.5f, 1e-6f);  // phi = 45 of 90 degrees
  const float theta = std::acos(0.25f), theta0 = std::acos(-0.5f), theta1 = std::acos(0.75f);
  EXPECT_NEAR(hit->uv.y, (theta - theta0) / (theta1 - theta0), 1e-5f);
  // A ray straight down x = y = 0.3 crosses the sphere at z = +-1.95: above z_max and below z_min, both cut away.
  EXPECT_FALSE(intersect_quadric(q, {0.3f, 0.3f, 10.0f}, {0, 0, -1}, 0.0f, kInfinity));
  // Through the open quadrants (x < 0): the near side is cut away, the far side (x > 0, y > 0) is hit from inside.
  const auto far = intersect_quadric(q, {-10.0f, -10.0f, 0.5f}, -d, 0.0f, kInfinity);
  ASSERT_TRUE(far);
  EXPECT_EQ(far->root, 1u);
  EXPECT_NEAR(far->t, 10.0f * std::sqrt(2.0f) + ring, kRel * 16.0f);
}

// Quadrics of every kind, placed by rotations and non-uniform scales, some reversed, among a few triangles.
WorldGeometry quadric_scene() {
  WorldGeometry g;
  TriangleMesh ground;
  ground.p = {{-10, 0, -10}, {10, 0, -10}, {10, 0, 10}, {-10, 0, 10}};
  ground.idx = {0, 2, 1, 0, 3, 2};
  add_mesh(g, ground);
  const Transform up = Transform::rotate(-90.0f, {1, 0, 0});  // object z -> world y
  add_quadric(g, quadric(QuadricType::Disk, 1.0f, 0.3f, 0.5f, 0, 0, 300.0f),
              Transform::translate({-3, 0.5f, 0}) * up, true);
  add_quadric(g, quadric(QuadricType::Disk, 1.5f, 0.0f, 0.0f, 0, 0, 360.0f),
              Transform::translate({0, 3.5f, -2}) * Transform::rotate(50.0f, {1, 0.2f, 0}));
  add_quadric(g, quadric(QuadricType::Cylinder, 0.8f, 0, 0, 0.0f, 2.5f, 250.0f),
              Transform::translate({2.5f, 0, 0}) * up * Transform::scale({1.0f, 0.6f, 1.0f}));
  add_quadric(g, quadric(QuadricType::Cylinder, 0.4f, 0, 0, -1.0f, 1.0f, 360.0f),
              Transform::translate({0, 1, 2}) * Transform::rotate(30.0f, {0, 0, 1}));
  add_quadric(g, quadric(QuadricType::Sphere, 1.2f, 0, 0, -0.6f, 1.2f, 290.0f),
              Transform::translate({0, 1.2f, 0}) * up * Transform::scale({1.3f, 1.0f, 0.9f}), true);
  add_quadric(g, quadric(QuadricType::Sphere, 0.9f, 0, 0, 0.0f, 0.9f, 360.0f), Transform::translate({-1, 0, 3}) * up);
  return g;
}

Ray camera_ray(size_t, Rng& rng) {
  const Vec3f eye(0, 4, 10);
  const Frame f(normalize(Vec3f(0, 1, 0) - eye));
  const Vec2f u = rng.next_2d();
  return Ray{eye, f.to_world(Vec3f((u.x - 0.5f) * 1.2f, (u.y - 0.5f) * 1.2f, 1.0f))};
}

TEST(CheckBvh, AgreesOnEveryQuadric) {
  const WorldGeometry g = quadric_scene();
  const CheckBvhReport r = check_bvh(g, camera_ray, CheckBvhOptions{});
  EXPECT_TRUE(r.passed) << r.to_json();
  EXPECT_EQ(r.total_disagreements(), 0u) << r.first_disagreement;
  EXPECT_GT(r.bounce.rays, 50000u);
}

TEST(CheckBvh, AgreesOnMovingQuadricsAtEveryInstant) {
  WorldGeometry g = quadric_scene();
  for (size_t i = 1; i < g.shapes.size(); ++i) g.shapes[i].motion = Vec3f(0.3f * float(i) - 1.0f, 0.2f, 0.5f);
  g.has_motion = true;
  const CheckBvhReport r = check_bvh(g, at_random_instants(camera_ray), CheckBvhOptions{});
  EXPECT_TRUE(r.passed) << r.to_json();
  EXPECT_EQ(r.total_disagreements(), 0u) << r.first_disagreement;
}

// pbrt's animated transforms (ActiveTransform): every quadric turns a different way about a different axis and
// moves, some also grow, so both accelerators take each ray into a different object space at each instant.
TEST(CheckBvh, AgreesOnAnimatedQuadricsAtEveryInstant) {
  WorldGeometry g = quadric_scene();
  for (size_t i = 1; i < g.shapes.size(); ++i) {
    const float k = float(i);
    const Transform& start = g.quadrics[g.shapes[i].index].to_world;
    const Transform end = Transform::translate({0.4f * k - 1.5f, 0.3f, -0.5f}) *
                          Transform::rotate(25.0f * k, {std::sin(k), 1.0f, std::cos(k)}) * start *
                          Transform::scale(Vec3f(i % 2 ? 1.0f : 1.3f));
    g.motions.emplace_back(start, 0.0f, end, 1.0f);
    g.shapes[i].animated = int32_t(g.motions.size() - 1);
  }
  g.has_motion = true;
  const CheckBvhReport r = check_bvh(g, at_random_instants(camera_ray), CheckBvhOptions{});
  EXPECT_TRUE(r.passed) << r.to_json();
  EXPECT_EQ(r.total_disagreements(), 0u) << r.first_disagreement;
  EXPECT_GT(r.bounce.rays, 50000u);
}

TEST(CheckBvh, DetectsAQuadricMissingFromTheBvh) {
  const WorldGeometry g = quadric_scene();
  const EmbreeAccel embree(g);
  BvhOptions o;
  o.debug_drop_primitive = 2 + 4;  // two ground triangles first; the fifth quadric is the partial ellipsoid
  const Bvh broken(g, o);
  const CheckBvhReport r = check_bvh(g, embree, broken, camera_ray, CheckBvhOptions{.rays = 20000});
  EXPECT_FALSE(r.passed);
  EXPECT_GT(r.camera.bvh_faults, 100u) << r.to_json();
}

TEST(QuadricHit, BothAcceleratorsReportTheSameHitAndTheOrientedNormal) {
  const WorldGeometry g = quadric_scene();
  const EmbreeAccel embree(g);
  const Bvh bvh(g);
  Rng rng(4, 4);
  int quadric_hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray r = camera_ray(size_t(i), rng);
    Hit a, b;
    const bool ha = embree.intersect(r, a), hb = bvh.intersect(r, b);
    ASSERT_EQ(ha, hb);
    if (!ha) continue;
    ASSERT_EQ(a.shape, b.shape);
    const Shape& s = g.shapes[a.shape];
    if (s.kind != ShapeKind::Quadric) continue;  // (triangles: Embree's own test, equal within ulps)
    EXPECT_EQ(a.t, b.t);  // the same object-space ray through the same code
    EXPECT_EQ(a.u, b.u);
    EXPECT_EQ(a.v, b.v);
    EXPECT_EQ(a.ng, b.ng);
    ++quadric_hits;
    // The normal is the natural one through the transform, reversed for flipped shapes.
    const QuadricShape& q = g.quadrics[s.index];
    const Vec3f p_obj = quadric_object_point(q, r, a.t);
    Vec3f n = normalize(q.to_world.normal(q.quadric.normal(p_obj)));
    if (q.flip) n = -n;
    EXPECT_GT(dot(normalize(a.ng), n), 0.9999f);
    // The reported (u, v) are the surface's at the hit point.
    const Vec2f uv = q.quadric.uv(p_obj);
    EXPECT_NEAR(a.u, uv.x, 1e-5f);
    EXPECT_NEAR(a.v, uv.y, 1e-5f);
    EXPECT_LT(length(surface_point(g, r, a).p - r.at(a.t)), 1e-4f * a.t);
  }
  EXPECT_GT(quadric_hits, 2000);
}

}  // namespace
}  // namespace kiln
