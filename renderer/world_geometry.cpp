#include "renderer/world_geometry.h"

#include "renderer/accel/shape_bounds.h"

namespace kiln {

Bounds3f WorldGeometry::bounds() const { return geometry_bounds(*this); }

size_t WorldGeometry::triangle_count() const { return geometry_triangle_count(*this); }

}  // namespace kiln
