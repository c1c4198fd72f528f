// Axis-aligned bounding box.
#pragma once
#include "core/vec.h"

namespace kiln {

struct Bounds3f {
  Vec3f lo{kInfinity}, hi{-kInfinity};
  Bounds3f() = default;
  Bounds3f(Vec3f a, Vec3f b) : lo(min(a, b)), hi(max(a, b)) {}
  explicit Bounds3f(Vec3f p) : lo(p), hi(p) {}
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(Vec3f p) { lo = min(lo, p); hi = max(hi, p); }
  void extend(const Bounds3f& b) { lo = min(lo, b.lo); hi = max(hi, b.hi); }
  Vec3f diagonal() const { return hi - lo; }
  Vec3f center() const { return (lo + hi) * 0.5f; }
  float surface_area() const {
    if (empty()) return 0.0f;
    const Vec3f d = diagonal();
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
  }
  float extent() const { return empty() ? 0.0f : length(diagonal()); }
};

inline Bounds3f merge(Bounds3f a, const Bounds3f& b) { a.extend(b); return a; }

}  // namespace kiln
