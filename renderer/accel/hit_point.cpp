#include "renderer/accel/hit_point.h"

#include "renderer/accel/object_ray.h"

namespace kiln {

Vec3f triangle_world_normal(const WorldGeometry& g, uint32_t shape, uint32_t prim) {
  const Shape& s = g.shapes[shape];
  const TriangleMesh& m = s.kind == ShapeKind::Mesh ? g.meshes[s.index] : g.prototypes[g.instances[s.index].prototype];
  const Vec3f v0 = m.vertex(prim, 0);
  const Vec3f n = cross(m.vertex(prim, 1) - v0, m.vertex(prim, 2) - v0);
  if (s.kind == ShapeKind::Mesh) return n;
  const Transform& xf = g.instances[s.index].to_world;
  const Vec3f nw = xf.normal(n);
  return xf.swaps_handedness() ? -nw : nw;
}

Vec3f sphere_world_normal(const SphereShape& s, const Ray& ray, float t) {
  if (s.to_world.is_identity()) return ray.o + ray.d * t - s.center;
  Vec3f o = ray.o, d = ray.d;
  to_object_space(s.to_world.inverse(), o, d);
  return s.to_world.normal(o + d * t - s.center);
}

Vec3f hit_point(const WorldGeometry& g, const Ray& ray, const Hit& hit) {
  const Shape& s = g.shapes[hit.shape];
  if (s.kind == ShapeKind::Sphere) {
    const SphereShape& sph = g.spheres[s.index];
    const bool xf = !sph.to_world.is_identity();
    Vec3f o = ray.o, d = ray.d;
    if (xf) to_object_space(sph.to_world.inverse(), o, d);
    const Vec3f rel = o + d * hit.t - sph.center;
    const float len = length(rel);
    const Vec3f p = len > 0.0f ? sph.center + rel * (sph.radius / len) : sph.center + rel;
    return xf ? sph.to_world.point(p) : p;
  }
  const TriangleMesh& m = s.kind == ShapeKind::Mesh ? g.meshes[s.index] : g.prototypes[g.instances[s.index].prototype];
  const float b0 = 1.0f - hit.u - hit.v;
  const Vec3f p = m.vertex(hit.prim, 0) * b0 + m.vertex(hit.prim, 1) * hit.u + m.vertex(hit.prim, 2) * hit.v;
  return s.kind == ShapeKind::Mesh ? p : g.instances[s.index].to_world.point(p);
}

}  // namespace kiln
