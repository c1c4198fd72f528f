// The surface point and geometric normal of a hit: the one step from an accelerator's Hit to the surface that
// shading (renderer/world/interaction.h), the BVH cross-check and the stability tests all start from. The point is rebuilt
// from the primitive (barycentric interpolation of the vertices; projection back onto the sphere) rather than taken
// as o + t d, whose error grows with the ray length and could exceed the offset that offset_ray_origin adds.
#pragma once
#include "renderer/accel/accelerator.h"

namespace kiln {

struct SurfacePoint {
  Vec3f p;   // world space
  Vec3f ng;  // unit geometric normal: (v1-v0)x(v2-v0) of the world triangle, outward for spheres
  // Magnitude whose ulps bound p's error when it exceeds p's own (offset_ray_origin's extent): for instance hits the
  // transform's translation plus its scaled object-space point, since the accelerator intersects in object space.
  float extent = 0.0f;
};

// kMeshesOnly: every shape is a static world-space mesh (no spheres, no instances, no motion), so the shape dispatch
// is compiled out. A moving shape is resolved at the ray's time.
template <bool kMeshesOnly = false>
SurfacePoint surface_point(const WorldGeometry& g, const Ray& ray, const Hit& hit);

// (v1-v0)x(v2-v0) of triangle prim of a Mesh or Instance shape, in world space, not normalised. For an instance this
// is the object-space normal through the inverse transpose, sign-corrected when the transform mirrors, so it points
// the same way as the cross product of the transformed vertices would.
Vec3f triangle_world_normal(const WorldGeometry& g, uint32_t shape, uint32_t prim);

// Unnormalised outward normal, in world space, of a sphere/ellipsoid hit at parameter t of the world-space ray.
Vec3f sphere_world_normal(const SphereShape& s, const Ray& ray, float t);

// The point of a quadric hit at parameter t of the world-space ray, in the quadric's object space (on its surface).
Vec3f quadric_object_point(const QuadricShape& q, const Ray& ray, float t);
// Unnormalised normal, in world space, of a quadric hit at parameter t of the world-space ray: the natural normal
// (core/quadric.h) through the transform, reversed when QuadricShape::flip is set.
Vec3f quadric_world_normal(const QuadricShape& q, const Ray& ray, float t);

}  // namespace kiln
