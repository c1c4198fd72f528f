#include "renderer/world/interaction.h"

#include "renderer/accel/surface_point.h"

#include <algorithm>
#include <cmath>

namespace kiln {
namespace {

Vec3f interpolated_normal(const std::vector<Vec3f>& n, const TriangleMesh& m, const Hit& hit) {
  const uint32_t* idx = &m.idx[3 * size_t(hit.prim)];
  return n[idx[0]] * (1.0f - hit.u - hit.v) + n[idx[1]] * hit.u + n[idx[2]] * hit.v;
}

// The interpolated per-vertex normal of a smooth mesh or instance, in world space, not normalised (an animated
// instance's at the ray's time).
template <bool kMeshesOnly>
Vec3f smooth_normal(const World& world, const ShapeData& sd, const Hit& hit, float time) {
  const Shape& shape = world.geometry.shapes[hit.shape];
  const std::vector<Vec3f>& normals = world.normals[size_t(sd.normals)];
  if (kMeshesOnly || shape.kind == ShapeKind::Mesh)
    return interpolated_normal(normals, world.geometry.meshes[shape.index], hit);
  const MeshInstance& inst = world.geometry.instances[shape.index];
  const Vec3f n = interpolated_normal(normals, world.geometry.prototypes[inst.prototype], hit);
  return shape.animated >= 0 ? shape_to_world(world.geometry, shape, time).normal(n) : inst.to_world.normal(n);
}

// dp/du and dp/dv of a triangle from its corners and their uv (pbrt's triangle derivatives); a frame around the face
// normal when the uv are missing or degenerate.
void triangle_derivatives(const Vec3f p[3], const Vec2f uv[3], Vec3f& dpdu, Vec3f& dpdv) {
  const Vec2f d02 = uv[0] - uv[2], d12 = uv[1] - uv[2];
  const Vec3f dp02 = p[0] - p[2], dp12 = p[1] - p[2];
  const float det = d02.x * d12.y - d02.y * d12.x;
  if (std::fabs(det) > 1e-12f) {
    const float inv = 1.0f / det;
    dpdu = (dp02 * d12.y - dp12 * d02.y) * inv;
    dpdv = (dp12 * d02.x - dp02 * d12.x) * inv;
    if (length_squared(cross(dpdu, dpdv)) > 0.0f) return;
  }
  Vec3f n = cross(p[1] - p[0], p[2] - p[0]);
  n = length_squared(n) > 0.0f ? normalize(n) : Vec3f(0, 0, 1);
  coordinate_system(n, dpdu, dpdv);
}

// uv and its derivatives on triangle `prim` of mesh m (object space; `to_world` maps the derivatives).
void triangle_texture_frame(const TriangleMesh& m, const std::vector<Vec2f>* uvs, const Hit& hit,
                            const Transform* to_world, SurfaceInteraction& si) {
  const uint32_t* idx = &m.idx[3 * size_t(hit.prim)];
  const Vec3f p[3] = {m.p[idx[0]], m.p[idx[1]], m.p[idx[2]]};
  Vec2f uv[3] = {{0, 0}, {1, 0}, {1, 1}};  // pbrt's default parametrisation when the mesh has none
  if (uvs) uv[0] = (*uvs)[idx[0]], uv[1] = (*uvs)[idx[1]], uv[2] = (*uvs)[idx[2]];
  const float b0 = 1.0f - hit.u - hit.v;
  si.uv = uv[0] * b0 + uv[1] * hit.u + uv[2] * hit.v;
  triangle_derivatives(p, uv, si.dpdu, si.dpdv);
  if (to_world) {
    si.dpdu = to_world->vector(si.dpdu);
    si.dpdv = to_world->vector(si.dpdv);
  }
}

// Course sphere mapping (spec §8), in the sphere's own frame: theta = acos(y/r), phi = atan2(z, x),
// u = (pi - phi) / (2 pi), v = theta / pi. With phi = pi - 2 pi u and theta = pi v:
// dp/du = 2 pi (z, 0, -x), dp/dv = pi (y cos phi, -r sin theta, y sin phi).
void sphere_texture_frame(const SphereShape& s, const Transform& to_world, SurfaceInteraction& si) {
  const bool xf = !to_world.is_identity();
  const Vec3f local = (xf ? to_world.inverse().point(si.p) : si.p) - s.center;
  const float r = s.radius;
  const float cos_theta = std::clamp(local.y / r, -1.0f, 1.0f);
  const float theta = std::acos(cos_theta), phi = std::atan2(local.z, local.x);
  si.uv = Vec2f((kPi - phi) / (2.0f * kPi), theta / kPi);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  Vec3f dpdu = Vec3f(local.z, 0.0f, -local.x) * (2.0f * kPi);
  Vec3f dpdv = Vec3f(local.y * std::cos(phi), -r * sin_theta, local.y * std::sin(phi)) * kPi;
  if (xf) {
    dpdu = to_world.vector(dpdu);
    dpdv = to_world.vector(dpdv);
  }
  if (length_squared(cross(dpdu, dpdv)) > 0.0f) {
    si.dpdu = dpdu;
    si.dpdv = dpdv;
  } else {  // a pole: any frame around the normal
    coordinate_system(si.ng, si.dpdu, si.dpdv);
  }
}

// pbrt-v4's quadric parametrisation (core/quadric.h): the accelerators report (u, v) in the hit.
void quadric_texture_frame(const QuadricShape& q, const Ray& ray, const Hit& hit, SurfaceInteraction& si) {
  si.uv = Vec2f(hit.u, hit.v);
  Vec3f dpdu, dpdv;
  q.quadric.derivatives(quadric_object_point(q, ray, hit.t), dpdu, dpdv);
  dpdu = q.to_world.vector(dpdu);
  dpdv = q.to_world.vector(dpdv);
  if (length_squared(cross(dpdu, dpdv)) > 0.0f) {
    si.dpdu = dpdu;
    si.dpdv = dpdv;
  } else {  // the disk's centre, a sphere's pole: any frame around the normal
    coordinate_system(si.ng, si.dpdu, si.dpdv);
  }
}

// A moving sphere, instance or quadric is taken where the ray found it.
template <bool kMeshesOnly>
void texture_frame(const World& world, const ShapeData& sd, const Ray& ray, const Hit& hit, SurfaceInteraction& si) {
  const float time = ray.time;
  const Shape& shape = world.geometry.shapes[hit.shape];
  const std::vector<Vec2f>* uvs = sd.uvs >= 0 ? &world.uvs[size_t(sd.uvs)] : nullptr;
  const ShapeKind kind = kMeshesOnly ? ShapeKind::Mesh : shape.kind;
  switch (kind) {
    case ShapeKind::Mesh: triangle_texture_frame(world.geometry.meshes[shape.index], uvs, hit, nullptr, si); break;
    case ShapeKind::Instance: {
      const MeshInstance& inst = world.geometry.instances[shape.index];
      const Transform to_world = shape.moving() ? shape_to_world(world.geometry, shape, time) : inst.to_world;
      triangle_texture_frame(world.geometry.prototypes[inst.prototype], uvs, hit, &to_world, si);
      break;
    }
    case ShapeKind::Sphere: {
      const SphereShape& s = world.geometry.spheres[shape.index];
      sphere_texture_frame(s, shape.moving() ? shape_to_world(world.geometry, shape, time) : s.to_world, si);
      break;
    }
    case ShapeKind::Quadric: {
      Ray back = ray;  // a moving quadric, where the ray found it
      if (shape.translates()) back.o -= shape.offset_at(ray.time);
      quadric_texture_frame(quadric_at(world.geometry, shape, time), back, hit, si);
      break;
    }
  }
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
  si.hit_uv = Vec2f(hit.u, hit.v);
  if (sd.material >= 0) {
    const int m = world.features & kFeatureMix ? choose_mixed_material(world.mixes, sd.material, si.p, -ray.d)
                                                : sd.material;
    si.material = &world.materials[size_t(m)];
  }
  si.light = sd.light;
  if (sd.normals >= 0) {
    const Vec3f ns = smooth_normal<kMeshesOnly>(world, sd, hit, ray.time);
    if (length_squared(ns) > 0.0f) {
      const Vec3f n = normalize(ns);
      si.ns = dot(n, si.ng) < 0.0f ? -n : n;
    }
  }
  if (sd.textures >= 0) {
    si.textures = sd.textures;
    si.wo = -ray.d;
    texture_frame<kMeshesOnly>(world, sd, ray, hit, si);
  }
  return si;
}

template SurfaceInteraction make_interaction<false>(const World&, const Ray&, const Hit&);
template SurfaceInteraction make_interaction<true>(const World&, const Ray&, const Hit&);

}  // namespace kiln
