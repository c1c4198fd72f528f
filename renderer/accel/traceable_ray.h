// The rays both accelerators accept. Embree 3 (as Debian builds it, with assertions) aborts the process on a ray
// with a NaN or huge (> 1.8e18) origin or direction component, or a NaN tmin/tmax; one bad sample must not kill a
// render, so such rays are treated as missing everything, by both accelerators alike.
#pragma once
#include "core/ray.h"

namespace kiln {

inline constexpr float kMaxTraceableCoordinate = 1.8e18f;  // Embree's FLT_LARGE, just below it

inline bool traceable(const Ray& r) {
  // Every comparison is false for NaN, so NaN components fail too (std::max would drop them).
  bool ok = r.tmin == r.tmin && r.tmax == r.tmax;
  for (int a = 0; a < 3; ++a)
    ok &= std::abs(r.o[a]) <= kMaxTraceableCoordinate && std::abs(r.d[a]) <= kMaxTraceableCoordinate;
  return ok;
}

}  // namespace kiln
