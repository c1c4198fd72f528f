// Ray-sphere intersection shared by both accelerators.
//
// The textbook b^2 - 4ac discriminant loses all precision when the ray starts far from a small sphere (b^2 and ac
// are huge and nearly equal). Following Haines et al., "Precision Improvements for Ray/Sphere Intersection"
// (Ray Tracing Gems ch. 7): the discriminant is computed from the vector l between the centre and the point of
// the line closest to it, r^2 - |l|^2, whose terms are small; the near root comes from c/q and the far root from
// q/a, so neither suffers cancellation. Coordinates are taken relative to the centre, so spheres far from the
// world origin keep their precision. No epsilon is applied to tmin: callers offset spawned origins themselves
// (core/ray.h offset_ray_origin).
#pragma once
#include <optional>

#include "core/vec.h"

namespace kiln {

struct SphereRoots {
  float t0, t1;  // t0 <= t1
};

// Both parameters where o + t d meets the sphere (centre c, radius r), or nothing when the line misses it.
inline std::optional<SphereRoots> sphere_roots(Vec3f o, Vec3f d, Vec3f c, float r) {
  const Vec3f f = o - c;
  const float a = dot(d, d);
  const float b = -dot(f, d);  // the closest point of the line to c is at t = b / a
  const Vec3f l = f + d * (b / a);
  const float r2 = r * r;
  const float disc = a * (r2 - dot(l, l));
  if (!(disc >= 0.0f)) return std::nullopt;  // also rejects NaN (zero direction)
  const float c_term = dot(f, f) - r2;
  const float q = b + std::copysign(std::sqrt(disc), b);
  if (q == 0.0f) return SphereRoots{0.0f, 0.0f};  // origin on the sphere and ray tangent there
  float t0 = c_term / q, t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  return SphereRoots{t0, t1};
}

// Nearest parameter in [tmin, tmax] where the ray meets the sphere.
inline std::optional<float> intersect_sphere(Vec3f o, Vec3f d, Vec3f c, float r, float tmin, float tmax) {
  const auto roots = sphere_roots(o, d, c, r);
  if (!roots) return std::nullopt;
  if (roots->t0 >= tmin && roots->t0 <= tmax) return roots->t0;
  if (roots->t1 >= tmin && roots->t1 <= tmax) return roots->t1;
  return std::nullopt;
}

}  // namespace kiln
