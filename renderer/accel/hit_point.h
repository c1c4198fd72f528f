// Reconstructing the surface point and normal of a Hit. The point is rebuilt from the primitive (barycentric
// interpolation of the vertices; projection back onto the sphere) rather than taken as o + t d, whose error grows
// with the ray length and could exceed the offset that offset_ray_origin adds.
#pragma once
#include "renderer/accel/accelerator.h"

namespace kiln {

// (v1-v0)x(v2-v0) of triangle prim of a Mesh or Instance shape, in world space. For an instance this is the
// object-space normal through the inverse transpose, sign-corrected when the transform mirrors, so it points the
// same way as the cross product of the transformed vertices would.
Vec3f triangle_world_normal(const WorldGeometry& g, uint32_t shape, uint32_t prim);

// Unnormalised outward normal, in world space, of a sphere/ellipsoid hit at parameter t of the world-space ray.
Vec3f sphere_world_normal(const SphereShape& s, const Ray& ray, float t);

// World-space point of a valid hit of ray.
Vec3f hit_point(const WorldGeometry& g, const Ray& ray, const Hit& hit);

}  // namespace kiln
