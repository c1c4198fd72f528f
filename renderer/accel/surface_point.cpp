#include "renderer/accel/surface_point.h"

#include <algorithm>
#include <cmath>

#include "renderer/accel/object_ray.h"

namespace kiln {
namespace {

Vec3f unit_or_z(Vec3f n) {
  const float len = length(n);
  return len > 0.0f ? n / len : Vec3f(0, 0, 1);
}

// A bound on the magnitudes summed when M maps p to world space: |translation| + max|linear entry| * |p|, per the
// largest components. The world point's rounding error, and the object-space ray's, are ulps of this.
float transformed_extent(const Transform& xf, Vec3f p) {
  const auto& m = xf.matrix().m;
  float linear = 0.0f, translation = 0.0f;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) linear = std::max(linear, std::abs(m[r][c]));
    translation = std::max(translation, std::abs(m[r][3]));
  }
  return translation + 3.0f * linear * max_component(abs(p));
}

// Barycentric position from the triangle's own vertices: far more precise than ray.o + t * ray.d far from the
// origin, which keeps the ulp-based spawn offset valid.
Vec3f barycentric_point(const TriangleMesh& m, const Hit& hit) {
  return m.vertex(hit.prim, 0) * (1.0f - hit.u - hit.v) + m.vertex(hit.prim, 1) * hit.u + m.vertex(hit.prim, 2) * hit.v;
}

SurfacePoint on_sphere(const SphereShape& s, const Transform& to_world, const Ray& ray, float t) {
  const bool xf = !to_world.is_identity();
  Vec3f o = ray.o, d = ray.d;
  if (xf) to_object_space(to_world.inverse(), o, d);
  const Vec3f rel = o + d * t - s.center;
  const float len = length(rel);
  const Vec3f dir = len > 0.0f ? rel / len : Vec3f(0, 0, 1);
  const Vec3f p = s.center + dir * s.radius;
  return xf ? SurfacePoint{to_world.point(p), unit_or_z(to_world.normal(dir)), transformed_extent(to_world, p)}
            : SurfacePoint{p, dir};
}

SurfacePoint on_instance(const WorldGeometry& g, const MeshInstance& inst, const Transform& to_world, const Hit& hit) {
  const TriangleMesh& m = g.prototypes[inst.prototype];
  const Vec3f p_object = barycentric_point(m, hit);
  const Vec3f a = m.vertex(hit.prim, 0);
  const Vec3f n = to_world.normal(cross(m.vertex(hit.prim, 1) - a, m.vertex(hit.prim, 2) - a));
  return {to_world.point(p_object), unit_or_z(to_world.swaps_handedness() ? -n : n),
          transformed_extent(to_world, p_object)};
}

SurfacePoint on_quadric(const QuadricShape& q, const Ray& ray, float t) {
  const Vec3f p = quadric_object_point(q, ray, t);
  return {q.to_world.point(p), unit_or_z(quadric_world_normal(q, ray, t)), transformed_extent(q.to_world, p)};
}

// The shape as it is at time 0, hit by `ray`.
SurfacePoint static_surface_point(const WorldGeometry& g, const Shape& s, ShapeKind kind, const Ray& ray,
                                  const Hit& hit) {
  switch (kind) {
    case ShapeKind::Mesh:  // both accelerators report (v1-v0)x(v2-v0) as a world mesh's hit.ng
      return {barycentric_point(g.meshes[s.index], hit), unit_or_z(hit.ng)};
    case ShapeKind::Instance: {
      const MeshInstance& inst = g.instances[s.index];
      const Vec3f p_object = barycentric_point(g.prototypes[inst.prototype], hit);
      return {inst.to_world.point(p_object), unit_or_z(triangle_world_normal(g, hit.shape, hit.prim)),
              transformed_extent(inst.to_world, p_object)};
    }
    case ShapeKind::Sphere: return on_sphere(g.spheres[s.index], g.spheres[s.index].to_world, ray, hit.t);
    case ShapeKind::Quadric: return on_quadric(g.quadrics[s.index], ray, hit.t);
  }
  return {};
}

}  // namespace

template <bool kMeshesOnly>
SurfacePoint surface_point(const WorldGeometry& g, const Ray& ray, const Hit& hit) {
  const Shape& s = g.shapes[hit.shape];
  const ShapeKind kind = kMeshesOnly ? ShapeKind::Mesh : s.kind;
  if (kMeshesOnly || !s.moving()) return static_surface_point(g, s, kind, ray, hit);
  if (s.animated >= 0) {  // where the animated transform has the shape at the ray's time
    if (kind == ShapeKind::Quadric) return on_quadric(quadric_at(g, s, ray.time), ray, hit.t);
    const Transform to_world = g.motions[size_t(s.animated)].at(ray.time);
    return kind == ShapeKind::Sphere ? on_sphere(g.spheres[s.index], to_world, ray, hit.t)
                                     : on_instance(g, g.instances[s.index], to_world, hit);
  }
  // A moving shape, where the ray found it: the ray shifted back by the shape's offset at its time meets the shape
  // at time 0 at the same t; the point found there moves forward by that offset (a translation keeps normals).
  const Vec3f offset = s.offset_at(ray.time);
  Ray back = ray;
  back.o -= offset;
  SurfacePoint sp = static_surface_point(g, s, kind, back, hit);
  sp.p += offset;
  return sp;
}

template SurfacePoint surface_point<false>(const WorldGeometry&, const Ray&, const Hit&);
template SurfacePoint surface_point<true>(const WorldGeometry&, const Ray&, const Hit&);

Vec3f triangle_world_normal(const WorldGeometry& g, uint32_t shape, uint32_t prim, float time) {
  const Shape& s = g.shapes[shape];
  const TriangleMesh& m = s.kind == ShapeKind::Mesh ? g.meshes[s.index] : g.prototypes[g.instances[s.index].prototype];
  const Vec3f v0 = m.vertex(prim, 0);
  const Vec3f n = cross(m.vertex(prim, 1) - v0, m.vertex(prim, 2) - v0);
  if (s.kind == ShapeKind::Mesh) return n;
  if (s.animated >= 0) {
    const Transform xf = g.motions[size_t(s.animated)].at(time);
    const Vec3f nw = xf.normal(n);
    return xf.swaps_handedness() ? -nw : nw;
  }
  const Transform& xf = g.instances[s.index].to_world;
  const Vec3f nw = xf.normal(n);
  return xf.swaps_handedness() ? -nw : nw;
}

Vec3f sphere_world_normal(const SphereShape& s, const Ray& ray, float t) {
  return sphere_world_normal(s, s.to_world, ray, t);
}

Vec3f sphere_world_normal(const SphereShape& s, const Transform& to_world, const Ray& ray, float t) {
  if (to_world.is_identity()) return ray.o + ray.d * t - s.center;
  Vec3f o = ray.o, d = ray.d;
  to_object_space(to_world.inverse(), o, d);
  return to_world.normal(o + d * t - s.center);
}

}  // namespace kiln

namespace kiln {

Vec3f quadric_object_point(const QuadricShape& q, const Ray& ray, float t) {
  Vec3f o = ray.o, d = ray.d;
  to_object_space(q.to_world.inverse(), o, d);
  return q.quadric.project(o + d * t);
}

Vec3f quadric_world_normal(const QuadricShape& q, const Ray& ray, float t) {
  const Vec3f n = q.to_world.normal(q.quadric.normal(quadric_object_point(q, ray, t)));
  return q.flip ? -n : n;
}

}  // namespace kiln
