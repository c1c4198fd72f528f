// World-space bounds of the shapes accelerators are built over; WorldGeometry::bounds and
// WorldGeometry::triangle_count delegate here.
#pragma once
#include <cstddef>

#include "renderer/accel/geometry.h"

namespace kiln {

// Tight bounds of a (possibly ellipsoidal) sphere: for an affine map the extent along world axis i is the radius
// times the length of row i of the linear part.
Bounds3f sphere_world_bounds(const SphereShape& s);
Bounds3f mesh_bounds(const TriangleMesh& m);
Bounds3f quadric_world_bounds(const QuadricShape& q);
Bounds3f instance_world_bounds(const WorldGeometry& g, const MeshInstance& inst);
// At time 0 (shape_static_bounds) and over the whole shutter interval (shape_world_bounds): a translation sweeps
// a box along a straight line, so the union of its two end boxes bounds every instant; an animated shape's box is
// its object-space box through AnimatedTransform::motion_bounds.
Bounds3f shape_static_bounds(const WorldGeometry& g, const Shape& s);
Bounds3f shape_world_bounds(const WorldGeometry& g, const Shape& s);
// In the shape's own space: the sphere's cube, the quadric's or instance prototype's or the (world-space) mesh's box.
Bounds3f shape_object_bounds(const WorldGeometry& g, const Shape& s);
Bounds3f swept_bounds(const Bounds3f& at_time0, Vec3f motion);

Bounds3f geometry_bounds(const WorldGeometry& g);
size_t geometry_triangle_count(const WorldGeometry& g);  // instanced triangles counted once per instance

}  // namespace kiln
