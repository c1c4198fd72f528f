// pbrt-v4's alpha test, shared by both accelerators: a candidate hit on a shape with an alpha cut-out is kept with
// probability equal to the shape's opacity a there. a >= 1 keeps it, a <= 0 passes through it, and between the two
// the hit is kept when a hash of the ray and the hit, uniform in [0, 1), falls below a (pbrt-v4 hashes the ray; the
// hit's shape, primitive and root are added so that two cut-outs along one ray decide independently). The hash is
// deterministic, so a ray and every re-trace of it (Embree may test a primitive in several leaves; check-bvh asks
// both accelerators) decide alike, and an image stays bit-identical for any thread count. The expected transmission
// through a surface is exactly 1 - a.
#pragma once
#include <bit>

#include "core/ray.h"
#include "core/rng.h"
#include "renderer/accel/geometry.h"

namespace kiln {

// Uniform in [0, 1): a hash of the world-space ray and the hit it is asked about.
inline float alpha_hash(const Ray& world_ray, uint32_t shape, uint32_t prim, uint32_t root) {
  uint64_t h = mix64((uint64_t(shape) << 32) | prim) ^ root;
  for (const float f : {world_ray.o.x, world_ray.o.y, world_ray.o.z, world_ray.d.x, world_ray.d.y, world_ray.d.z})
    h = mix64(h ^ std::bit_cast<uint32_t>(f));
  return float(h >> 40) * 0x1p-24f;
}

// Whether a candidate hit on a shape with Shape::alpha set is kept (hit_uv: see AlphaTest).
inline bool alpha_keeps(const WorldGeometry& g, const Ray& world_ray, uint32_t shape, uint32_t prim, Vec2f hit_uv,
                        uint32_t root) {
  const float a = g.alpha.opacity(g.alpha.world, shape, prim, hit_uv, world_ray.time);
  if (a >= 1.0f) return true;
  if (!(a > 0.0f)) return false;
  return alpha_hash(world_ray, shape, prim, root) < a;
}

}  // namespace kiln
