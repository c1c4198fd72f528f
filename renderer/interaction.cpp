#include "renderer/interaction.h"

namespace kiln {
namespace {

// Barycentric position from the triangle's own vertices: far more precise than ray.o + t * ray.d far from the
// origin, which keeps the ulp-based spawn offset valid.
Vec3f barycentric(Vec3f a, Vec3f b, Vec3f c, float u, float v) { return a * (1.0f - u - v) + b * u + c * v; }

Vec3f interpolated_normal(const std::vector<Vec3f>& n, const TriangleMesh& m, uint32_t prim, float u, float v) {
  const Vec3f r = barycentric(n[m.idx[3 * prim]], n[m.idx[3 * prim + 1]], n[m.idx[3 * prim + 2]], u, v);
  const float len = length(r);
  return len > 0.0f ? r / len : Vec3f(0.0f);
}

}  // namespace

template <bool kMeshesOnly>
SurfaceInteraction make_interaction(const World& world, const Ray& ray, const Hit& hit) {
  SurfaceInteraction si;
  si.t = hit.t;
  si.shape = hit.shape;
  si.prim = hit.prim;
  const Shape& shape = world.geometry.shapes[hit.shape];
  const ShapeData& sd = world.shape_data[hit.shape];
  si.material = sd.material >= 0 ? &world.materials[size_t(sd.material)] : nullptr;
  si.light = sd.light;
  Vec3f ns(0.0f);
  const ShapeKind kind = kMeshesOnly ? ShapeKind::Mesh : shape.kind;
  switch (kind) {
    case ShapeKind::Mesh: {
      const TriangleMesh& m = world.geometry.meshes[shape.index];
      const Vec3f a = m.vertex(hit.prim, 0), b = m.vertex(hit.prim, 1), c = m.vertex(hit.prim, 2);
      si.p = barycentric(a, b, c, hit.u, hit.v);
      si.ng = cross(b - a, c - a);
      if (sd.normals >= 0) ns = interpolated_normal(world.normals[size_t(sd.normals)], m, hit.prim, hit.u, hit.v);
      break;
    }
    case ShapeKind::Instance: {
      const MeshInstance& inst = world.geometry.instances[shape.index];
      const TriangleMesh& m = world.geometry.prototypes[inst.prototype];
      const Vec3f a = m.vertex(hit.prim, 0), b = m.vertex(hit.prim, 1), c = m.vertex(hit.prim, 2);
      si.p = inst.to_world.point(barycentric(a, b, c, hit.u, hit.v));
      si.ng = inst.to_world.normal(cross(b - a, c - a));
      if (inst.to_world.swaps_handedness()) si.ng = -si.ng;  // keep (v1-v0)x(v2-v0) of the world triangle
      if (sd.normals >= 0)
        ns = inst.to_world.normal(interpolated_normal(world.normals[size_t(sd.normals)], m, hit.prim, hit.u, hit.v));
      break;
    }
    case ShapeKind::Sphere: {
      const SphereShape& s = world.geometry.spheres[shape.index];
      // Re-project the hit onto the sphere in object space so the spawn offset starts from the surface.
      const Vec3f po = s.to_world.inverse().point(ray.at(hit.t));
      Vec3f d = po - s.center;
      const float len = length(d);
      d = len > 0.0f ? d / len : Vec3f(0, 0, 1);
      si.p = s.to_world.point(s.center + d * s.radius);
      si.ng = s.to_world.normal(d);
      break;
    }
  }
  const float lg = length(si.ng);
  si.ng = lg > 0.0f ? si.ng / lg : Vec3f(0, 0, 1);
  if (length_squared(ns) > 0.0f) {
    ns = normalize(ns);
    si.ns = dot(ns, si.ng) < 0.0f ? -ns : ns;
  } else {
    si.ns = si.ng;
  }
  return si;
}

template SurfaceInteraction make_interaction<false>(const World&, const Ray&, const Hit&);
template SurfaceInteraction make_interaction<true>(const World&, const Ray&, const Hit&);

}  // namespace kiln
