// Alpha cut-outs in both accelerators (renderer/accel/alpha.h): a surface of opacity a stops exactly a fraction a
// of the rays (binomial limits), for closest-hit and occlusion queries alike; a cut-out pattern lets rays through its
// open cells only, to whatever lies behind; on triangles, instances and quadrics; Embree and the BVH agree ray by ray
// (check-bvh, whose referee applies the alpha test at the exact hit).
#include <gtest/gtest.h>

#include <cmath>

#include "accel_test_util.h"
#include "renderer/accel/alpha.h"
#include "renderer/accel/bvh.h"
#include "renderer/accel/check_bvh.h"
#include "renderer/accel/embree_accel.h"

namespace kiln {
namespace {

using namespace kiln::test;

// The opacities the test world gives its shapes: per shape a constant, or (negative) a checkerboard of 4 x 4 cells
// over the hit coordinates, opaque on even cells.
struct TestOpacity {
  std::vector<float> per_shape;
  static float opacity(const void* self, uint32_t shape, uint32_t, Vec2f hit, float) {
    const float a = static_cast<const TestOpacity*>(self)->per_shape[shape];
    if (a >= 0.0f) return a;
    return (int(std::floor(hit.x * 4.0f)) + int(std::floor(hit.y * 4.0f))) % 2 == 0 ? 1.0f : 0.0f;
  }
};

constexpr float kChecker = -1.0f;

void set_alpha(WorldGeometry& g, TestOpacity& o, uint32_t shape, float a) {
  o.per_shape.resize(g.shapes.size(), 1.0f);
  o.per_shape[shape] = a;
  g.shapes[shape].alpha = true;
  g.alpha = AlphaTest{&TestOpacity::opacity, &o};
}

// A quad in z = 0 over [-1, 1]^2 (triangles (v1-v0)x(v2-v0) = +z) and a backstop quad at z = -1.
WorldGeometry quad_and_backstop() {
  WorldGeometry g;
  TriangleMesh quad;
  quad.p = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.idx = {0, 1, 2, 0, 2, 3};
  add_mesh(g, quad);
  TriangleMesh back = quad;
  for (Vec3f& p : back.p) p = p * 2.0f + Vec3f(0, 0, -1);
  add_mesh(g, back);
  return g;
}

TEST(Alpha, ASurfaceOfOpacityAStopsExactlyThatFractionOfRays) {
  for (const float a : {0.0f, 0.3f, 0.75f, 1.0f}) {
    WorldGeometry g = quad_and_backstop();
    TestOpacity o;
    set_alpha(g, o, 0, a);
    const EmbreeAccel embree(g);
    const Bvh bvh(g);
    constexpr int kRays = 40000;
    int stopped = 0, occluded = 0;
    Rng rng(17, 3);
    for (int i = 0; i < kRays; ++i) {
      const Vec3f o_ray(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 2.0f);
      const Ray r{o_ray, normalize(Vec3f(0.1f * (rng.next_float() - 0.5f), 0.1f * (rng.next_float() - 0.5f), -1))};
      Hit he, hb;
      ASSERT_TRUE(embree.intersect(r, he));
      ASSERT_TRUE(bvh.intersect(r, hb));
      ASSERT_EQ(he.shape, hb.shape) << "the two accelerators decide alike";
      stopped += he.shape == 0;
      Ray shadow = r;
      shadow.tmax = 2.5f;  // ends between the quad and the backstop
      const bool oe = embree.occluded(shadow), ob = bvh.occluded(shadow);
      ASSERT_EQ(oe, ob);
      occluded += oe;
    }
    // Binomial: 5 standard deviations of kRays draws with probability a.
    const double sd = std::sqrt(kRays * a * (1.0 - a)), expected = kRays * double(a);
    EXPECT_NEAR(stopped, expected, 5.0 * sd + 0.5) << "opacity " << a;
    EXPECT_EQ(occluded, stopped) << "opacity " << a << ": shadow rays decide as closest-hit rays do";
  }
}

TEST(Alpha, ACutOutPatternPassesRaysThroughItsOpenCellsOnly) {
  // The quad's barycentric coordinates make a checkerboard on each triangle; the disk's surface (u, v) one on it.
  WorldGeometry g = quad_and_backstop();
  const uint32_t disk = add_quadric(g, *make_quadric(QuadricType::Disk, 0.9f, 0.0f, 0.5f, 0, 0, 360.0f).quadric);
  TestOpacity o;
  set_alpha(g, o, 0, kChecker);
  set_alpha(g, o, disk, kChecker);
  for (const bool use_bvh : {false, true}) {
    const std::unique_ptr<Accelerator> accel =
        use_bvh ? std::unique_ptr<Accelerator>(std::make_unique<Bvh>(g)) : std::make_unique<EmbreeAccel>(g);
    Rng rng(2, 9);
    int through = 0;
    for (int i = 0; i < 20000; ++i) {
      const Ray r{Vec3f(2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f, 3.0f), {0, 0, -1}};
      Hit h;
      ASSERT_TRUE(accel->intersect(r, h));
      if (h.shape == 1) {
        ++through;
        continue;
      }
      // Every kept hit lies on an opaque cell.
      EXPECT_EQ(TestOpacity::opacity(&o, h.shape, h.prim, {h.u, h.v}, 0.0f), 1.0f) << h.shape;
    }
    EXPECT_GT(through, 2000) << "rays pass the open cells of both cut-outs";
  }
}

// check_scene's kinds of shapes with cut-outs: a fractional-opacity ground, a checkered icosphere, checkered
// instances and quadrics, some moving.
TEST(CheckBvh, AgreesOnAlphaCutOuts) {
  WorldGeometry g;
  TriangleMesh ground;
  ground.p = {{-10, 0, -10}, {10, 0, -10}, {10, 0, 10}, {-10, 0, 10}};
  ground.idx = {0, 2, 1, 0, 3, 2};
  const uint32_t ground_id = add_mesh(g, ground);
  const uint32_t ball = add_mesh(g, make_icosphere(3, Vec3f(-2, 1, 0), 1.0f));
  add_mesh(g, make_icosphere(2, Vec3f(0, -3, 0), 2.0f));  // under the ground: seen through it
  const uint32_t proto = add_prototype(g, make_icosphere(2));
  std::vector<uint32_t> instances;
  for (int i = 0; i < 4; ++i)
    instances.push_back(add_instance(
        g, proto, Transform::translate(Vec3f(float(i) * 2.0f - 3.0f, 0.5f, -4)) * Transform::scale(Vec3f(0.5f))));
  const uint32_t cyl = add_quadric(g, *make_quadric(QuadricType::Cylinder, 0.7f, 0, 0, 0, 2, 360).quadric,
                                   Transform::translate({2, 0, 0}) * Transform::rotate(-90.0f, {1, 0, 0}));
  const uint32_t dome = add_quadric(g, *make_quadric(QuadricType::Sphere, 1.0f, 0, 0, 0, 1, 360).quadric,
                                    Transform::translate({0, 0, 2}) * Transform::rotate(-90.0f, {1, 0, 0}));
  TestOpacity o;
  set_alpha(g, o, ground_id, 0.6f);
  for (const uint32_t s : {ball, cyl, dome}) set_alpha(g, o, s, kChecker);
  for (const uint32_t s : instances) set_alpha(g, o, s, s % 2 ? kChecker : 0.5f);
  g.shapes[cyl].motion = Vec3f(0.4f, 0.0f, 0.3f);
  g.shapes[instances[1]].motion = Vec3f(0.0f, 0.5f, 0.0f);
  g.has_motion = true;
  const auto ray = [](size_t, Rng& rng) {
    const Vec3f eye(0, 4, 10);
    const Frame f(normalize(Vec3f(0, 0, 0) - eye));
    const Vec2f u = rng.next_2d();
    return Ray{eye, f.to_world(Vec3f((u.x - 0.5f) * 1.2f, (u.y - 0.5f) * 1.2f, 1.0f))};
  };
  const CheckBvhReport r = check_bvh(g, at_random_instants(ray), CheckBvhOptions{});
  EXPECT_TRUE(r.passed) << r.to_json();
  EXPECT_EQ(r.total_disagreements(), 0u) << r.first_disagreement;
}

TEST(Alpha, TheHashIsUniformAndDependsOnRayAndHit) {
  const Ray r{{0.1f, 0.2f, 0.3f}, normalize(Vec3f(1, 2, 3))};
  EXPECT_EQ(alpha_hash(r, 1, 2, 0), alpha_hash(r, 1, 2, 0));
  EXPECT_NE(alpha_hash(r, 1, 2, 0), alpha_hash(r, 1, 2, 1));
  EXPECT_NE(alpha_hash(r, 1, 2, 0), alpha_hash(r, 1, 3, 0));
  std::vector<uint64_t> counts(16, 0);
  Rng rng(3, 3);
  for (int i = 0; i < 160000; ++i) {
    const Ray q{{rng.next_float(), rng.next_float(), rng.next_float()}, random_direction(rng)};
    const float u = alpha_hash(q, uint32_t(i % 7), uint32_t(i % 5), 0);
    ASSERT_TRUE(u >= 0.0f && u < 1.0f);
    ++counts[size_t(u * 16.0f)];
  }
  for (uint64_t c : counts) EXPECT_NEAR(double(c), 10000.0, 5.0 * std::sqrt(10000.0 * 15.0 / 16.0));
}

}  // namespace
}  // namespace kiln
