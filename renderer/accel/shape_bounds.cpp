#include "renderer/accel/shape_bounds.h"

namespace kiln {

Bounds3f sphere_world_bounds(const SphereShape& s) {
  const auto& m = s.to_world.matrix().m;
  const bool affine = m[3][0] == 0.0f && m[3][1] == 0.0f && m[3][2] == 0.0f && m[3][3] == 1.0f;
  const Bounds3f object(s.center - Vec3f(s.radius), s.center + Vec3f(s.radius));
  if (!affine) return s.to_world.bounds(object);
  const Vec3f c = s.to_world.point(s.center);
  Vec3f half;
  for (int i = 0; i < 3; ++i) half[i] = s.radius * length(Vec3f(m[i][0], m[i][1], m[i][2]));
  return {c - half, c + half};
}

Bounds3f mesh_bounds(const TriangleMesh& m) {
  Bounds3f b;
  // Only referenced vertices count: unused vertices must not inflate the box.
  for (uint32_t i : m.idx) b.extend(m.p[i]);
  return b;
}

namespace {
// A quadric's box, widened: the transformed corners are rounded to float while hits are computed through the
// transform in double, and a few ulps of padding keep every surface point inside the box.
Bounds3f padded(Bounds3f b) {
  const float pad = 0x1p-20f * std::max(max_component(abs(b.lo)), max_component(abs(b.hi)));
  b.lo -= Vec3f(pad);
  b.hi += Vec3f(pad);
  return b;
}
}  // namespace

Bounds3f quadric_world_bounds(const QuadricShape& q) { return padded(q.to_world.bounds(q.quadric.bounds())); }

Bounds3f instance_world_bounds(const WorldGeometry& g, const MeshInstance& inst) {
  return inst.to_world.bounds(mesh_bounds(g.prototypes[inst.prototype]));
}

Bounds3f shape_static_bounds(const WorldGeometry& g, const Shape& s) {
  switch (s.kind) {
    case ShapeKind::Mesh:
      return mesh_bounds(g.meshes[s.index]);
    case ShapeKind::Sphere:
      return sphere_world_bounds(g.spheres[s.index]);
    case ShapeKind::Instance:
      return instance_world_bounds(g, g.instances[s.index]);
    case ShapeKind::Quadric:
      return quadric_world_bounds(g.quadrics[s.index]);
  }
  return {};
}

Bounds3f swept_bounds(const Bounds3f& at_time0, Vec3f motion) {
  if (at_time0.empty()) return at_time0;
  Bounds3f b = at_time0;
  b.extend(at_time0.lo + motion);
  b.extend(at_time0.hi + motion);
  return b;
}

Bounds3f shape_object_bounds(const WorldGeometry& g, const Shape& s) {
  if (s.kind == ShapeKind::Sphere) {
    const SphereShape& sp = g.spheres[s.index];
    return {sp.center - Vec3f(sp.radius), sp.center + Vec3f(sp.radius)};
  }
  if (s.kind == ShapeKind::Instance) return mesh_bounds(g.prototypes[g.instances[s.index].prototype]);
  if (s.kind == ShapeKind::Quadric) return padded(g.quadrics[s.index].quadric.bounds());
  return mesh_bounds(g.meshes[s.index]);
}

Bounds3f shape_world_bounds(const WorldGeometry& g, const Shape& s) {
  if (s.animated >= 0) return g.motions[size_t(s.animated)].motion_bounds(shape_object_bounds(g, s));
  const Bounds3f b = shape_static_bounds(g, s);
  return s.translates() ? swept_bounds(b, s.motion) : b;
}

Transform shape_to_world(const WorldGeometry& g, const Shape& s, float time) {
  if (s.animated >= 0) return g.motions[size_t(s.animated)].at(time);
  const Transform& xf = s.kind == ShapeKind::Sphere     ? g.spheres[s.index].to_world
                        : s.kind == ShapeKind::Instance ? g.instances[s.index].to_world
                        : s.kind == ShapeKind::Quadric  ? g.quadrics[s.index].to_world
                                                        : Transform();
  return s.translates() ? Transform::translate(s.offset_at(time)) * xf : xf;
}

QuadricShape quadric_at(const WorldGeometry& g, const Shape& s, float time) {
  QuadricShape q = g.quadrics[s.index];
  if (s.animated >= 0) q.to_world = g.motions[size_t(s.animated)].at(time);
  return q;
}

Bounds3f geometry_bounds(const WorldGeometry& g) {
  Bounds3f b;
  for (const Shape& s : g.shapes) b.extend(shape_world_bounds(g, s));
  return b;
}

size_t geometry_triangle_count(const WorldGeometry& g) {
  size_t n = 0;
  for (const Shape& s : g.shapes) {
    if (s.kind == ShapeKind::Mesh) n += g.meshes[s.index].triangle_count();
    if (s.kind == ShapeKind::Instance) n += g.prototypes[g.instances[s.index].prototype].triangle_count();
  }
  return n;
}

Bounds3f WorldGeometry::bounds() const { return geometry_bounds(*this); }

size_t WorldGeometry::triangle_count() const { return geometry_triangle_count(*this); }

}  // namespace kiln
