// Self-intersection: a ray spawned from a hit point must not hit the surface it leaves. The renderer rebuilds hit
// points from the primitive (make_interaction) and offsets them by ulps (core/ray.h spawn_ray); both have to work
// from 1e-8 to 1e8, the range where one fixed epsilon is always wrong somewhere.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/world/interaction.h"
#include "renderer/integrators/stability_util.h"

namespace kiln::test {
namespace {

constexpr int kScales = 40;
constexpr int kPrimaryRays = 120;
constexpr int kSpawnedPerHit = 4;
constexpr int kSoupTriangles = 6;

class Reintersection : public AccelParam {};

Vec3f random_unit(Rng& rng) { return sample_uniform_sphere(rng.next_2d()); }

// Random triangles, a sphere, an instanced (rotated, non-uniformly scaled) mesh and three pbrt quadrics (an annulus
// sector, an open cylinder, a sphere wedge; rotated) of size ~size, around a centre at distance ~scale from the origin.
SceneDesc scene_at(float scale, float size, Rng& rng) {
  SceneDesc s;
  s.format = "test";
  s.source_path = "reintersection";
  BrdfDesc lambert;
  lambert.kind = BrdfKind::Lambert;
  s.brdfs.push_back(lambert);
  MaterialDesc m;
  m.brdf = 0;
  m.diffuse = Rgb(0.5f);
  s.materials.push_back(m);
  const Vec3f c = random_unit(rng) * scale;
  MeshDesc soup;
  soup.name = "soup";
  soup.material = 0;
  for (int t = 0; t < kSoupTriangles; ++t) {
    const Vec3f base = c + random_unit(rng) * (2.0f * size);
    for (int k = 0; k < 3; ++k) {
      soup.positions.push_back(base + random_unit(rng) * size);
      soup.indices.push_back(uint32_t(soup.positions.size() - 1));
    }
  }
  s.meshes.push_back(soup);
  MeshDesc proto;
  proto.name = "prototype";
  proto.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0.3f}, {-1, 1, -0.2f}};
  proto.indices = {0, 1, 2, 0, 2, 3};
  proto.material = 0;
  proto.is_instance_base = true;
  proto.visible = false;
  s.meshes.push_back(proto);
  InstanceDesc inst;
  inst.name = "instance";
  inst.base_mesh = 1;
  inst.to_world = Transform::translate(c + random_unit(rng) * (3.0f * size)) *
                  Transform::rotate(360.0f * rng.next_float(), random_unit(rng)) *
                  Transform::scale(Vec3f(size, 0.5f * size, -1.5f * size));
  s.instances.push_back(inst);
  SphereDesc sphere;
  sphere.name = "sphere";
  sphere.center = c + random_unit(rng) * (3.0f * size);
  sphere.radius = size;
  sphere.material = 0;
  s.spheres.push_back(sphere);
  const QuadricOrError quadrics[] = {make_quadric(QuadricType::Disk, size, 0.3f * size, 0.0f, 0, 0, 300.0f),
                                     make_quadric(QuadricType::Cylinder, size, 0, 0, -size, size, 250.0f),
                                     make_quadric(QuadricType::Sphere, size, 0, 0, -0.5f * size, size, 270.0f)};
  for (const QuadricOrError& q : quadrics) {
    QuadricDesc d;
    d.name = "quadric";
    d.quadric = *q.quadric;
    d.to_world = Transform::translate(c + random_unit(rng) * (3.0f * size)) *
                 Transform::rotate(360.0f * rng.next_float(), random_unit(rng));
    d.material = 0;
    s.quadrics.push_back(d);
  }
  return s;
}

// The radius of a curved shape that a spawned ray may cross (a chord away) after leaving it inwards; 0 for flat ones.
float curved_radius(const World& w, const Shape& sh) {
  if (sh.kind == ShapeKind::Sphere) return w.geometry.spheres[sh.index].radius;
  if (sh.kind != ShapeKind::Quadric) return 0.0f;
  const Quadric& q = w.geometry.quadrics[sh.index].quadric;
  return q.type == QuadricType::Disk ? 0.0f : q.radius;
}

// The j-th ray spawned from si: even j a continuation towards dir, odd j a shadow ray to a point 10 sizes away.
Ray spawned_ray(const SurfaceInteraction& si, Vec3f dir, int j, float size) {
  return j % 2 == 0 ? spawn_ray(si.p, si.ng, dir, 0.0f, si.extent)
                    : spawn_ray_to(si.p, si.ng, si.p + dir * (10.0f * size), 0.0f, si.extent);
}

// A point on shape `shape` of the world (roughly uniform; only used as an aim point).
Vec3f point_on(const World& w, uint32_t shape, Rng& rng) {
  const Shape& sh = w.geometry.shapes[shape];
  const Vec2f b = sample_uniform_triangle(rng.next_2d());
  auto on_triangle = [&](const TriangleMesh& m, const Transform* xf) {
    const size_t tri = std::min(size_t(rng.next_float() * float(m.triangle_count())), m.triangle_count() - 1);
    const Vec3f p = m.vertex(tri, 0) * (1.0f - b.x - b.y) + m.vertex(tri, 1) * b.x + m.vertex(tri, 2) * b.y;
    return xf ? xf->point(p) : p;
  };
  switch (sh.kind) {
    case ShapeKind::Mesh:
      return on_triangle(w.geometry.meshes[sh.index], nullptr);
    case ShapeKind::Instance: {
      const MeshInstance& in = w.geometry.instances[sh.index];
      return on_triangle(w.geometry.prototypes[in.prototype], &in.to_world);
    }
    case ShapeKind::Sphere: {
      const SphereShape& sp = w.geometry.spheres[sh.index];
      return sp.center + random_unit(rng) * (0.9f * sp.radius);
    }
    case ShapeKind::Quadric: {
      const QuadricShape& q = w.geometry.quadrics[sh.index];
      return q.to_world.point(q.quadric.sample_area(rng.next_2d()));
    }
  }
  return {};
}

// Why: the spawned continuation (any direction: reflection or transmission side) and the shadow ray towards a
// light must never report the surface they start on: that is shadow acne (black speckles) or a lost bounce.
// The hardest cases are spheres smaller than ~1e-4 near the origin: any fixed absolute nudge exceeds their radius
// (inward rays start past the centre and hit the far side at t ~ 0), which is why core/ray.h sizes the offset by
// 256 ulps of the hit point's largest coordinate.
TEST_P(Reintersection, SpawnedRaysDoNotHitTheirOwnSurface) {
  Rng rng(77, 1);
  size_t spawned = 0, self_hits = 0;
  std::string first;
  for (int k = 0; k < kScales; ++k) {
    const float scale = std::pow(10.0f, -8.0f + 16.0f * rng.next_float());  // log-uniform 1e-8 .. 1e8
    const float size = scale * std::pow(10.0f, -3.0f * rng.next_float());   // 1e-3 .. 1 of the distance
    const SceneDesc s = scene_at(scale, size, rng);
    const auto w = build_world(s, world_options());
    for (int i = 0; i < kPrimaryRays; ++i) {
      const uint32_t shape = uint32_t(i) % uint32_t(w->geometry.shapes.size());
      const Vec3f target = point_on(*w, shape, rng);
      const Vec3f o = target + random_unit(rng) * (8.0f * size);
      const Ray primary{o, target - o};
      Hit h;
      if (!w->accel->intersect(primary, h)) continue;
      const SurfaceInteraction si = make_interaction(*w, primary, h);
      const float radius = curved_radius(*w, w->geometry.shapes[h.shape]);
      for (int j = 0; j < kSpawnedPerHit; ++j) {
        const Vec3f dir = random_unit(rng);
        const Ray r = spawned_ray(si, dir, j, size);
        Hit h2;
        ++spawned;
        if (!w->accel->intersect(r, h2) || h2.shape != h.shape) continue;
        bool self;
        if (radius == 0.0f) {
          self = h2.prim == h.prim;  // a flat triangle or disk cannot be hit twice by one ray
        } else {
          // Leaving outwards must miss a sphere or cylinder; inwards, the far side is a chord at least 2 r cos away
          // (exactly, on a sphere), not ~0.
          const float cos_in = -dot(normalize(r.d), si.ng);
          self = cos_in <= 0.0f || h2.t * length(r.d) < radius * cos_in;
        }
        if (self) {
          ++self_hits;
          if (first.empty())
            first = "scale " + std::to_string(scale) + " size " + std::to_string(size) + " shape " +
                    std::to_string(h.shape) + " t " + std::to_string(h2.t) + (j % 2 ? " (shadow ray)" : "");
        }
      }
    }
  }
  EXPECT_GT(spawned, size_t(kScales * kPrimaryRays * kSpawnedPerHit) / 2);  // most primaries hit
  EXPECT_EQ(self_hits, 0u) << "of " << spawned << " spawned rays; first: " << first;
}

// An instance whose object-space geometry lies far from its own origin, moved back near the world origin: the
// prototype's plane at z = -T/2, placed by translate(0, 0, T) * scale(1, 1, 2) at world z = 0. The hit point is
// tiny, but the accelerator intersects in object space through a translation of T, so the spawn offset must be
// ulps of T (SurfacePoint::extent), not of the hit point; sized by the point alone, most shadow rays hit the plane
// they leave.
TEST_P(Reintersection, InstanceFarFromItsOwnOriginDoesNotShadowItself) {
  Rng rng(78, 1);
  size_t spawned = 0, self_hits = 0;
  std::string first;
  for (const float translation : {20.0f, 1e3f, 1e5f}) {
    for (const float size : {1e-3f, 1e-1f, 1.0f}) {
      SceneDesc s = scene_at(1.0f, 1.0f, rng);
      s.meshes.resize(1);
      s.meshes[0].positions = {{-size, -size, -0.5f * translation}, {size, -size, -0.5f * translation},
                               {size, size, -0.5f * translation}, {-size, size, -0.5f * translation}};
      s.meshes[0].indices = {0, 1, 2, 0, 2, 3};
      s.meshes[0].is_instance_base = true;
      s.meshes[0].visible = false;
      s.spheres.clear();
      s.quadrics.clear();
      s.instances.resize(1);
      s.instances[0].base_mesh = 0;
      s.instances[0].to_world = Transform::translate(Vec3f(0, 0, translation)) * Transform::scale(Vec3f(1, 1, 2));
      const auto w = build_world(s, world_options());
      for (int i = 0; i < kPrimaryRays; ++i) {
        const Vec3f target((2.0f * rng.next_float() - 1.0f) * size, (2.0f * rng.next_float() - 1.0f) * size, 0.0f);
        const Ray primary{target + Vec3f(0.3f, 0.2f, 1.0f) * size, Vec3f(-0.3f, -0.2f, -1.0f) * size};
        Hit h;
        if (!w->accel->intersect(primary, h)) continue;
        const SurfaceInteraction si = make_interaction(*w, primary, h);
        for (int j = 0; j < kSpawnedPerHit; ++j) {
          const Vec3f dir = random_unit(rng);
          const Ray r = spawned_ray(si, dir, j, size);
          Hit h2;
          ++spawned;
          if (w->accel->intersect(r, h2)) {  // the plane is the only shape: any hit is a self-hit
            ++self_hits;
            if (first.empty())
              first = "translation " + std::to_string(translation) + " size " + std::to_string(size) + " t " +
                      std::to_string(h2.t) + (j % 2 ? " (shadow ray)" : "");
          }
        }
      }
    }
  }
  EXPECT_GT(spawned, size_t(9 * kPrimaryRays * kSpawnedPerHit) / 2);
  EXPECT_EQ(self_hits, 0u) << "of " << spawned << " spawned rays; first: " << first;
}

KILN_INSTANTIATE_FOR_BOTH_ACCELS(Reintersection);

}  // namespace
}  // namespace kiln::test
