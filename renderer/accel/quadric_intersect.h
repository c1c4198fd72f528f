// Ray-quadric intersection (core/quadric.h) in the quadric's object space, shared by both accelerators so that they
// agree bit for bit. The cylinder and the sphere take their roots from sphere_roots (Haines et al.'s
// cancellation-free quadratic; the cylinder's is the same computation with z set aside), the disk from its plane.
// A root counts when it lies in [tmin, tmax], its point (put back onto the surface) lies within the shape's limits,
// and `keep` accepts it (the alpha test); the nearer root is tried first, so a cut-away or transparent near side
// lets the ray find the far one.
#pragma once
#include <optional>

#include "core/quadric.h"
#include "renderer/accel/sphere_intersect.h"

namespace kiln {

struct QuadricHit {
  float t = 0.0f;
  Vec2f uv;          // the surface parameters (core/quadric.h)
  uint32_t root = 0;  // 0: the nearer crossing of the line, 1: the farther one (the disk has one)
};

// keep(const QuadricHit&) -> bool.
template <class Keep>
std::optional<QuadricHit> intersect_quadric(const Quadric& q, Vec3f o, Vec3f d, float tmin, float tmax, Keep&& keep) {
  float roots[2];
  int n = 0;
  if (q.type == QuadricType::Disk) {
    if (d.z == 0.0f) return std::nullopt;  // parallel to the disk's plane
    roots[n++] = (q.height - o.z) / d.z;
  } else {
    const bool sphere = q.type == QuadricType::Sphere;
    if (!sphere && d.x == 0.0f && d.y == 0.0f) return std::nullopt;  // parallel to the cylinder's axis
    const auto r = sphere_roots(sphere ? o : Vec3f(o.x, o.y, 0.0f), sphere ? d : Vec3f(d.x, d.y, 0.0f), Vec3f(0.0f),
                                q.radius);
    if (!r) return std::nullopt;
    roots[n++] = r->t0;
    roots[n++] = r->t1;
  }
  for (int i = 0; i < n; ++i) {
    const float t = roots[i];
    if (!(t >= tmin && t <= tmax)) continue;
    const Vec3f p = q.project(o + d * t);
    if (!q.contains(p)) continue;
    const QuadricHit hit{t, q.uv(p), uint32_t(i)};
    if (keep(hit)) return hit;
  }
  return std::nullopt;
}

inline std::optional<QuadricHit> intersect_quadric(const Quadric& q, Vec3f o, Vec3f d, float tmin, float tmax) {
  return intersect_quadric(q, o, d, tmin, tmax, [](const QuadricHit&) { return true; });
}

}  // namespace kiln
