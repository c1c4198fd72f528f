// Rays into an object space (instances, ellipsoids). The direction is not renormalised, so a hit's t is the same
// in both spaces.
#pragma once
#include "core/transform.h"

namespace kiln {

// o and d through an affine world-to-object matrix, accumulated in double: the rounding of a float transform is
// the largest error of an instance or ellipsoid hit (it dominates the intersection test's own error for short
// rays), and doing it in double makes it a single rounding per component.
inline void to_object_space(const Transform& inv, Vec3f& o, Vec3f& d) {
  const auto& m = inv.matrix().m;
  if (m[3][0] != 0.0f || m[3][1] != 0.0f || m[3][2] != 0.0f || m[3][3] != 1.0f) {
    o = inv.point(o);  // projective: keep the homogeneous divide
    d = inv.vector(d);
    return;
  }
  Vec3f oo, dd;
  for (int i = 0; i < 3; ++i) {
    oo[i] = float(double(m[i][0]) * o.x + double(m[i][1]) * o.y + double(m[i][2]) * o.z + double(m[i][3]));
    dd[i] = float(double(m[i][0]) * d.x + double(m[i][1]) * d.y + double(m[i][2]) * d.z);
  }
  o = oo;
  d = dd;
}

}  // namespace kiln
