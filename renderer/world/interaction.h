// A ray-surface hit resolved for shading: position, normals, material and emitter.
#pragma once
#include "core/frame.h"
#include "core/ray.h"
#include "renderer/world/world.h"

namespace kiln {

struct SurfaceInteraction {
  Vec3f p;
  Vec3f ng;         // unit geometric normal; triangles: (v1-v0)x(v2-v0) after transformation, spheres: outward
  Vec3f ns;         // unit shading normal, in the same hemisphere as ng
  float t = 0;
  float extent = 0;  // offset_ray_origin's extent (renderer/accel/surface_point.h)
  const Material* material = nullptr;
  int light = -1;   // index into World::lights when the surface emits
  uint32_t shape = 0, prim = 0;
  Vec2f hit_uv;     // the accelerator's (u, v): barycentrics on triangles, the surface's (u, v) on quadrics
  // Set only on shapes with textures (ShapeData::textures >= 0); untextured hits leave them unset and unread.
  int textures = -1;  // index into World::textures->bindings
  Vec2f uv;           // texture coordinates (spec §7-§8: mesh vertices' uv, sphere (theta, phi) mapping)
  Vec3f dpdu, dpdv;   // world-space derivatives of p along u and v (never both zero: a frame around ng otherwise)
  Vec3f wo;           // -ray.d: what a mix with a textured amount hashes with p (renderer/world/material_mix.h)
};

// kMeshesOnly: the scene's feature mask has neither spheres nor instances, so every hit is on a world-space mesh
// and the shape dispatch is compiled out (the path tracer's specialisation; explicit instantiations for both).
template <bool kMeshesOnly = false>
SurfaceInteraction make_interaction(const World& world, const Ray& ray, const Hit& hit);

// Radiance the emitting surface at si (si.light >= 0) sends towards wo.
inline Rgb emitted_at(const World& world, const SurfaceInteraction& si, Vec3f wo) {
  return emitted(world.lights[size_t(si.light)], si.ng, wo, EmitterPoint{si.prim, si.hit_uv});
}

}  // namespace kiln
