#include "renderer/interaction.h"

#include "renderer/accel/surface_point.h"

namespace kiln {
namespace {

Vec3f interpolated_normal(const std::vector<Vec3f>& n, const TriangleMesh& m, const Hit& hit) {
  const uint32_t* idx = &m.idx[3 * size_t(hit.prim)];
  return n[idx[0]] * (1.0f - hit.u - hit.v) + n[idx[1]] * hit.u + n[idx[2]] * hit.v;
}

// The interpolated per-vertex normal of a smooth mesh or instance, in world space, not normalised.
template <bool kMeshesOnly>
Vec3f smooth_normal(const World& world, const ShapeData& sd, const Hit& hit) {
  const Shape& shape = world.geometry.shapes[hit.shape];
  const std::vector<Vec3f>& normals = world.normals[size_t(sd.normals)];
  if (kMeshesOnly || shape.kind == ShapeKind::Mesh)
    return interpolated_normal(normals, world.geometry.meshes[shape.index], hit);
  const MeshInstance& inst = world.geometry.instances[shape.index];
  return inst.to_world.normal(interpolated_normal(normals, world.geometry.prototypes[inst.prototype], hit));
}

}  // namespace

template <bool kMeshesOnly>
SurfaceInteraction make_interaction(const World& world, const Ray& ray, const Hit& hit) {
  const SurfacePoint sp = surface_point<kMeshesOnly>(world.geometry, ray, hit);
  const ShapeData& sd = world.shape_data[hit.shape];
  SurfaceInteraction si;
  si.p = sp.p;
  si.ng = sp.ng;
  si.extent = sp.extent;
  si.ns = sp.ng;
  si.t = hit.t;
  si.shape = hit.shape;
  si.prim = hit.prim;
  si.material = sd.material >= 0 ? &world.materials[size_t(sd.material)] : nullptr;
  si.light = sd.light;
  if (sd.normals >= 0) {
    const Vec3f ns = smooth_normal<kMeshesOnly>(world, sd, hit);
    if (length_squared(ns) > 0.0f) {
      const Vec3f n = normalize(ns);
      si.ns = dot(n, si.ng) < 0.0f ? -n : n;
    }
  }
  return si;
}

template SurfaceInteraction make_interaction<false>(const World&, const Ray&, const Hit&);
template SurfaceInteraction make_interaction<true>(const World&, const Ray&, const Hit&);

}  // namespace kiln
