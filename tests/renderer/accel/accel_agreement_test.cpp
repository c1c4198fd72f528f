// Embree and the BVH must agree ray by ray on every kind of geometry.
#include <gtest/gtest.h>

#include <cstdio>

#include "accel_test_util.h"
#include "renderer/accel/bvh.h"
#include "renderer/accel/check_bvh.h"
#include "renderer/accel/embree_accel.h"
#include "renderer/accel/shape_bounds.h"

namespace kiln {
namespace {

using namespace kiln::test;

constexpr size_t kRays = 20000;
// Float barycentrics of a small triangle seen from afar are only good to ~1e-4 in either implementation (both
// measured against a double-precision reference on the soup below: max error 9e-5); a real bug (swapped or
// misassigned barycentrics) is off by O(1).
constexpr float kBarycentricTolerance = 1e-3f;
constexpr float kEdgeBand = 1e-3f;    // barycentric distance to an edge that counts as grazing a silhouette
constexpr float kGrazingCos = 1e-2f;  // |cos| of a sphere hit that counts as grazing
const Vec3f kFarCentre(148376.0f, 1234.0f, -223423.0f);

struct Agreement {
  size_t rays = 0, hit_rays = 0, disagreements = 0, ties = 0, grazes = 0;
  float max_ulps = 0;  // largest hit-point difference, in ulps of the hit point
  std::string first;
};

float ulp(float x) {
  x = std::abs(x);
  return std::nextafter(x, kInfinity) - x;
}

// A hit that a float test may legitimately report or miss: a triangle hit within kEdgeBand of an edge (in a soup
// every edge is a silhouette) or a sphere hit at a grazing angle.
bool grazing(const WorldGeometry& g, const Ray& r, const Hit& h) {
  if (g.shapes[h.shape].kind == ShapeKind::Sphere) return absdot(normalize(h.ng), normalize(r.d)) < kGrazingCos;
  return std::min({1.0f - h.u - h.v, h.u, h.v}) < kEdgeBand;
}

// Closest hits and occlusion of random rays through the scene bounds, compared field by field.
Agreement compare_accels(const WorldGeometry& g, size_t rays, uint64_t seed) {
  const EmbreeAccel embree(g);
  const Bvh bvh(g);
  const Bounds3f b = geometry_bounds(g);
  Agreement a;
  Rng rng(seed, 0);
  for (size_t i = 0; i < rays; ++i) {
    Ray r = random_scene_ray(rng, b);
    if (i % 3 == 2) r.tmax = rng.next_float();  // segments ending anywhere, as shadow rays do
    Hit he, hb;
    const bool e = embree.intersect(r, he), h = bvh.intersect(r, hb);
    ++a.rays;
    a.hit_rays += e;
    EXPECT_EQ(embree.occluded(r), e) << "embree: occluded() must agree with intersect()";
    EXPECT_EQ(bvh.occluded(r), h) << "bvh: occluded() must agree with intersect()";
    bool bad = false;
    if (e != h) {
      if (grazing(g, r, e ? he : hb)) {
        ++a.grazes;
      } else {
        bad = true;
      }
    } else if (e) {
      // The distance criterion of check-bvh: relative tolerance, or hit points a few ulps apart (relative t is
      // too strict for very short rays, where Embree's own error exceeds it).
      const Vec3f p = r.at(he.t);
      const float dp = std::abs(he.t - hb.t) * length(r.d);
      const float ulps = dp / ulp(max_component(abs(p)));
      a.max_ulps = std::max(a.max_ulps, ulps);
      bad = std::abs(he.t - hb.t) > kCheckBvhDistanceTolerance * std::max(he.t, hb.t) && ulps > kCheckBvhHitPointUlps;
      if (!bad && (he.shape != hb.shape || he.prim != hb.prim)) {
        ++a.ties;
      } else if (!bad) {
        // Same primitive: the rest of the hit record must match too. Barycentrics are ill-conditioned for grazing
        // rays (an error e in t moves the point by e/cos(theta) within the plane), so their tolerance is too.
        const float cos_theta = std::abs(dot(normalize(he.ng), normalize(r.d)));
        const float uv_tol = kBarycentricTolerance / std::max(cos_theta, 1e-2f);
        bad = std::abs(he.u - hb.u) > uv_tol || std::abs(he.v - hb.v) > uv_tol ||
              dot(normalize(he.ng), normalize(hb.ng)) < 0.99999f;
      }
    }
    if (bad) {
      if (a.first.empty()) {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "ray %zu o=(%.9g, %.9g, %.9g) d=(%.9g, %.9g, %.9g) tmax %.9g: embree %d t=%.9g shape %u prim %u "
                      "uv %g %g; bvh %d t=%.9g shape %u prim %u uv %g %g",
                      i, r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.tmax, e, he.t, he.shape, he.prim, he.u, he.v, h,
                      hb.t, hb.shape, hb.prim, hb.u, hb.v);
        a.first = buf;
      }
      ++a.disagreements;
    }
  }
  return a;
}

void expect_agreement(const WorldGeometry& g, const char* what) {
  const Agreement a = compare_accels(g, kRays, 11);
  EXPECT_GT(a.hit_rays, a.rays / 10) << what << ": the rays must actually hit something";
  EXPECT_LE(double(a.disagreements), kCheckBvhMaxDisagreementRate * double(a.rays)) << what << ": " << a.first;
  EXPECT_LE(a.ties, a.rays / 1000) << what << ": edge ties should be rare";
  EXPECT_LE(a.grazes, a.rays / 1000) << what << ": silhouette grazes should be rare";
  std::printf("[ %s: %zu rays, %zu hits, %zu ties, %zu grazes, hit points differ by <= %.1f ulps ]\n", what, a.rays,
              a.hit_rays, a.ties, a.grazes, double(a.max_ulps));
}

TEST(AccelAgreement, RandomTriangleSoup) {
  WorldGeometry g;
  Rng rng(1, 2);
  add_mesh(g, make_triangle_soup(20000, rng, Bounds3f(Vec3f(-1.0f), Vec3f(1.0f)), 0.1f));
  add_mesh(g, make_triangle_soup(50, rng, Bounds3f(Vec3f(-1.0f), Vec3f(1.0f)), 1.5f));  // long slivers
  expect_agreement(g, "soup");
}

TEST(AccelAgreement, ClosedMesh) {
  WorldGeometry g;
  add_mesh(g, make_icosphere(5, Vec3f(0.3f, -0.2f, 0.1f), 2.0f));
  expect_agreement(g, "icosphere");
}

TEST(AccelAgreement, SpheresAndEllipsoids) {
  WorldGeometry g;
  add_sphere(g, Vec3f(0, 0, 0), 1.0f);
  add_sphere(g, Vec3f(2.5f, 0.5f, 0), 0.4f);
  add_sphere(g, Vec3f(-2, 1, 1), 1e-2f);
  add_sphere(g, Vec3f(0, 0, 0), 1.0f,
             Transform::translate(Vec3f(0, -2, 1)) * Transform::rotate(30, Vec3f(1, 1, 0)) *
                 Transform::scale(Vec3f(2.0f, 0.5f, 1.0f)));
  add_sphere(g, Vec3f(1, 0, 0), 0.5f, Transform::scale(Vec3f(-1.0f, 3.0f, 1.0f)));  // mirrored ellipsoid
  expect_agreement(g, "spheres");
}

TEST(AccelAgreement, Instances) {
  WorldGeometry g;
  const uint32_t ico = add_prototype(g, make_icosphere(3));
  Rng rng(5, 5);
  const uint32_t soup = add_prototype(g, make_triangle_soup(500, rng, Bounds3f(Vec3f(-1.0f), Vec3f(1.0f)), 0.3f));
  for (int i = 0; i < 12; ++i) {
    const Vec3f at(float(i % 4) * 2.5f - 4.0f, float(i / 4) * 2.5f - 2.5f, 0.0f);
    Transform xf = Transform::translate(at) * Transform::rotate(float(i) * 29.0f, Vec3f(0.2f, 1, 0.3f));
    if (i % 3 == 1) xf = xf * Transform::scale(Vec3f(1.0f, 0.5f, -0.8f));  // non-uniform and mirroring
    add_instance(g, i % 2 ? soup : ico, xf);
  }
  add_mesh(g, make_icosphere(2, Vec3f(0, 0, 3), 1.0f));  // a world mesh next to them
  add_sphere(g, Vec3f(0, 0, -3), 1.0f);
  g.prototypes.push_back(TriangleMesh{});  // unused prototype
  expect_agreement(g, "instances");
}

TEST(AccelAgreement, FarFromOrigin) {
  WorldGeometry g;
  Rng rng(2, 2);
  add_mesh(g, make_icosphere(4, kFarCentre, 3.0f));
  add_mesh(g, make_triangle_soup(2000, rng, Bounds3f(kFarCentre - Vec3f(10.0f), kFarCentre + Vec3f(10.0f)), 1.0f));
  add_sphere(g, kFarCentre + Vec3f(6, 0, 0), 2.0f);
  add_sphere(g, Vec3f(0, 0, 0), 1.0f,
             Transform::translate(kFarCentre + Vec3f(-6, 0, 0)) * Transform::scale(Vec3f(1.0f, 2.0f, 3.0f)));
  add_instance(g, add_prototype(g, make_icosphere(2)), Transform::translate(kFarCentre + Vec3f(0, 7, 0)));
  expect_agreement(g, "far from origin");
}

TEST(AccelAgreement, HitRecordOfAKnownTriangle) {
  // A unit right triangle instanced with a mirroring transform: both report the same Hit.
  WorldGeometry g;
  TriangleMesh tri;
  tri.p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.idx = {0, 1, 2};
  add_mesh(g, tri);
  add_instance(g, add_prototype(g, tri), Transform::translate(Vec3f(0, 0, 5)) * Transform::scale(Vec3f(-2, 2, 2)));
  for (bool use_bvh : {false, true}) {
    const auto acc = make_accelerator(use_bvh ? AccelKind::Bvh : AccelKind::Embree, g);
    Hit h;
    ASSERT_TRUE(acc->intersect(Ray{Vec3f(0.25f, 0.5f, -1), Vec3f(0, 0, 1)}, h));
    EXPECT_EQ(h.shape, 0u);
    EXPECT_EQ(h.prim, 0u);
    EXPECT_FLOAT_EQ(h.t, 1.0f);
    EXPECT_NEAR(h.u, 0.25f, 1e-6f);
    EXPECT_NEAR(h.v, 0.5f, 1e-6f);
    EXPECT_GT(h.ng.z, 0.0f) << "(v1-v0)x(v2-v0) of a CCW triangle seen from below points up";
    // The instance: world vertices (0,0,5), (-2,0,5), (0,2,5); their cross product points down.
    ASSERT_TRUE(acc->intersect(Ray{Vec3f(-0.5f, 1.0f, 6), Vec3f(0, 0, -1)}, h));
    EXPECT_EQ(h.shape, 1u);
    EXPECT_EQ(h.prim, 0u);
    EXPECT_FLOAT_EQ(h.t, 1.0f);
    EXPECT_NEAR(h.u, 0.25f, 1e-6f);
    EXPECT_NEAR(h.v, 0.5f, 1e-6f);
    EXPECT_LT(h.ng.z, 0.0f);
    EXPECT_NEAR(h.ng.x, 0.0f, 1e-6f);
    EXPECT_TRUE(acc->occluded(Ray{Vec3f(0.25f, 0.5f, -1), Vec3f(0, 0, 1), 0.0f, 1.0f}));
    EXPECT_FALSE(acc->occluded(Ray{Vec3f(0.25f, 0.5f, -1), Vec3f(0, 0, 1), 0.0f, 0.999f}));
    EXPECT_FALSE(acc->intersect(Ray{Vec3f(0.25f, 0.5f, -1), Vec3f(0, 0, 1), 1.001f, 4.999f}, h));
  }
}

TEST(AccelAgreement, EmptyAndSparseGeometry) {
  WorldGeometry empty;
  for (AccelKind k : {AccelKind::Embree, AccelKind::Bvh}) {
    const auto acc = make_accelerator(k, empty);
    Hit h;
    EXPECT_FALSE(acc->intersect(Ray{Vec3f(0.0f), Vec3f(0, 0, 1)}, h));
    EXPECT_FALSE(acc->occluded(Ray{Vec3f(0.0f), Vec3f(0, 0, 1)}));
    EXPECT_FALSE(h.valid());
  }
  WorldGeometry sparse;  // empty meshes and prototypes next to one sphere
  add_mesh(sparse, TriangleMesh{});
  add_instance(sparse, add_prototype(sparse, TriangleMesh{}), Transform());
  add_sphere(sparse, Vec3f(0, 0, 5), 1.0f);
  for (AccelKind k : {AccelKind::Embree, AccelKind::Bvh}) {
    const auto acc = make_accelerator(k, sparse);
    Hit h;
    ASSERT_TRUE(acc->intersect(Ray{Vec3f(0.0f), Vec3f(0, 0, 1)}, h));
    EXPECT_EQ(h.shape, 2u);
    EXPECT_FLOAT_EQ(h.t, 4.0f);
    EXPECT_LT(h.ng.z, 0.0f) << "outward normal";
  }
}

TEST(AccelAgreement, EmbreeSharesPaddedBuffersAndCopiesTightOnes) {
  // Same mesh held once with spare capacity (shared with Embree) and once exactly sized (copied): same hits.
  TriangleMesh padded = make_icosphere(2), tight = padded;
  padded.p.reserve(padded.p.size() + 1);
  padded.idx.reserve(padded.idx.size() + 1);
  tight.p.shrink_to_fit();
  tight.idx.shrink_to_fit();
  WorldGeometry a, b;
  add_mesh(a, padded);
  a.meshes[0].p.reserve(a.meshes[0].p.size() + 1);
  a.meshes[0].idx.reserve(a.meshes[0].idx.size() + 1);
  add_mesh(b, tight);
  const EmbreeAccel ea(a), eb(b);
  EXPECT_LT(ea.stats().bytes, eb.stats().bytes) << "sharing must save the vertex and index copies";
  Rng rng(4, 4);
  for (int i = 0; i < 2000; ++i) {
    const Ray r = random_scene_ray(rng, Bounds3f(Vec3f(-1.0f), Vec3f(1.0f)));
    Hit ha, hb;
    ASSERT_EQ(ea.intersect(r, ha), eb.intersect(r, hb));
    EXPECT_EQ(ha.t, hb.t);
    EXPECT_EQ(ha.prim, hb.prim);
  }
}

}  // namespace
}  // namespace kiln

namespace kiln {
namespace {

TEST(AccelAgreement, DegenerateRaysMissWithoutFaults) {
  WorldGeometry g;
  add_mesh(g, test::make_icosphere(2));
  add_sphere(g, Vec3f(3, 0, 0), 1.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (AccelKind k : {AccelKind::Embree, AccelKind::Bvh}) {
    const auto acc = make_accelerator(k, g);
    Hit h;
    EXPECT_FALSE(acc->intersect(Ray{Vec3f(0, 0, -5), Vec3f(0, 0, 1), 3.0f, 2.0f}, h)) << "tmin > tmax";
    EXPECT_FALSE(acc->occluded(Ray{Vec3f(0, 0, -5), Vec3f(0, 0, 1), 3.0f, 2.0f}));
    EXPECT_FALSE(acc->intersect(Ray{Vec3f(0, 0, -5), Vec3f(0, 0, 0)}, h)) << "zero direction";
    EXPECT_FALSE(acc->intersect(Ray{Vec3f(nan, 0, -5), Vec3f(0, 0, 1)}, h)) << "NaN origin";
    EXPECT_FALSE(acc->intersect(Ray{Vec3f(0, 0, -5), Vec3f(0, nan, 1)}, h)) << "NaN direction";
    EXPECT_FALSE(acc->occluded(Ray{Vec3f(0, 0, -5), Vec3f(0, nan, 1)})) << "NaN direction";
    EXPECT_FALSE(acc->intersect(Ray{Vec3f(0, 0, -5), Vec3f(0, 0, 1), nan, kInfinity}, h)) << "NaN tmin";
    EXPECT_FALSE(acc->intersect(Ray{Vec3f(0, 0, -1e30f), Vec3f(0, 0, 1)}, h)) << "beyond Embree's range";
    // Axis-aligned rays (zero direction components) through the middle still hit.
    EXPECT_TRUE(acc->intersect(Ray{Vec3f(0, 0, -5), Vec3f(0, 0, 1)}, h));
    EXPECT_TRUE(acc->intersect(Ray{Vec3f(-5, 0, 0), Vec3f(1, 0, 0)}, h));
    EXPECT_EQ(h.shape, 0u);
  }
}

}  // namespace
}  // namespace kiln
