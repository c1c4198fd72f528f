// Rays spawned with offset_ray_origin from hit points never hit their own surface again, at any scale.
#include <gtest/gtest.h>

#include <cmath>

#include "accel_test_util.h"
#include "renderer/accel/surface_point.h"

namespace kiln {
namespace {

using namespace kiln::test;

constexpr int kScales = 48;
constexpr int kPrimaryRays = 150;
constexpr int kSpawnedPerHit = 4;

// A quad (two triangles) and a sphere of size ~ size*scale placed at distance ~scale from the world origin.
WorldGeometry scene_at(float scale, float size, Rng& rng) {
  WorldGeometry g;
  const Vec3f c = random_direction(rng) * scale;
  const Vec3f n = random_direction(rng);
  Vec3f s, t;
  coordinate_system(n, s, t);
  const float h = 0.5f * size * scale;
  TriangleMesh quad;
  quad.p = {c - s * h - t * h, c + s * h - t * h, c + s * h + t * h, c - s * h + t * h};
  quad.idx = {0, 1, 2, 0, 2, 3};
  add_mesh(g, quad);
  const Vec3f c2 = c + random_direction(rng) * (3.0f * size * scale);
  add_sphere(g, c2, 0.5f * size * scale);
  return g;
}

TEST(Reintersection, SpawnedRaysDoNotHitTheirOwnSurface) {
  Rng rng(23, 0);
  size_t spawned = 0, self_hits = 0;
  std::string first;
  for (int k = 0; k < kScales; ++k) {
    // Coordinates log-uniform over 1e-8 .. 1e8; geometry size from 1e-3 to 1 of its distance to the origin.
    const float scale = std::pow(10.0f, -8.0f + 16.0f * rng.next_float());
    const float size = std::pow(10.0f, -3.0f * rng.next_float());
    const WorldGeometry g = scene_at(scale, size, rng);
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
      const auto acc = make_accelerator(kind, g);
      for (int i = 0; i < kPrimaryRays; ++i) {
        // Aim at a random point of the quad or the sphere from a few sizes away.
        const uint32_t target_shape = uint32_t(i % 2);
        Vec3f target;
        if (target_shape == 0) {
          const Vec2f u = rng.next_2d();
          const TriangleMesh& q = g.meshes[0];
          target = q.p[0] + (q.p[1] - q.p[0]) * u.x + (q.p[3] - q.p[0]) * u.y;
        } else {
          target = g.spheres[0].center + random_direction(rng) * (0.9f * g.spheres[0].radius);
        }
        const Vec3f o = target + random_direction(rng) * (4.0f * size * scale);
        const Ray primary{o, target - o};
        Hit h;
        if (!acc->intersect(primary, h)) continue;
        const Vec3f p = surface_point(g, primary, h).p;
        const Vec3f ng = normalize(h.ng);
        for (int j = 0; j < kSpawnedPerHit; ++j) {
          // Both sides: reflection-like and transmission-like directions.
          const Vec3f w = random_direction(rng);
          const Ray r = spawn_ray(p, ng, w);
          Hit h2;
          ++spawned;
          if (!acc->intersect(r, h2) || h2.shape != h.shape) continue;
          bool self = false;
          if (g.shapes[h.shape].kind == ShapeKind::Mesh) {
            self = true;  // a planar quad cannot be hit twice by one ray
          } else {
            // Leaving outwards must miss the sphere; inwards, the far side is a chord 2 r cos away, not ~0.
            const float cos_in = -dot(w, ng);
            const float chord = 2.0f * g.spheres[0].radius * cos_in;
            self = cos_in <= 0.0f || h2.t * length(w) < 0.5f * chord;
          }
          if (self) {
            ++self_hits;
            if (first.empty())
              first = acc->stats().name + " scale " + std::to_string(scale) + " size " + std::to_string(size) +
                      " shape " + std::to_string(h.shape) + " t2 " + std::to_string(h2.t);
          }
        }
      }
    }
  }
  EXPECT_GT(spawned, size_t(kScales * kPrimaryRays * kSpawnedPerHit));  // most primaries hit, on both accels
  EXPECT_EQ(self_hits, 0u) << "of " << spawned << " spawned rays; first: " << first;
}

}  // namespace
}  // namespace kiln
