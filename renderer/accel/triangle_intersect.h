// Watertight ray-triangle intersection (Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2013).
// The ray is sheared so that it runs along +z through the origin; the test is then a 2-D edge-function test on
// the sheared vertices. Neighbouring triangles evaluate a shared edge with bit-identical inputs, so a ray can
// never slip between them; edge functions that round to exactly zero are recomputed in double precision.
//
// The distance is not taken from the sheared edge functions (t = (U Az + V Bz + W Cz) / det), which cancel
// badly when the triangle is much larger than the hit distance: on a ground plane a bounce ray leaving the
// surface could find the plane again at t ~ 1e-6, in front of an origin offset_ray_origin had moved off it.
// Once the edge test has accepted the line, t is recomputed in double from the plane of the float vertices
// (edges and normal are then exact or nearly so), which is accurate to float rounding however large the
// triangle is, and only then compared with [tmin, tmax].
#pragma once
#include <utility>

#include "core/ray.h"

namespace kiln {

// Per-ray constants: the axis permutation (kz = dominant direction axis) and the shear.
struct WatertightRay {
  Vec3f o, d;
  int kx = 0, ky = 1, kz = 2;
  float sx = 0, sy = 0;
};

inline WatertightRay make_watertight_ray(const Ray& ray) {
  WatertightRay w;
  w.o = ray.o;
  w.d = ray.d;
  w.kz = max_dimension(abs(ray.d));
  w.kx = w.kz == 2 ? 0 : w.kz + 1;
  w.ky = w.kx == 2 ? 0 : w.kx + 1;
  if (ray.d[w.kz] < 0.0f) std::swap(w.kx, w.ky);  // keep the winding so the sign of det means the same side
  w.sx = ray.d[w.kx] / ray.d[w.kz];
  w.sy = ray.d[w.ky] / ray.d[w.kz];
  return w;
}

struct TriangleHit {
  float t, b1, b2;  // barycentrics of vertices 1 and 2
};

// Ray parameter where o + t d meets the plane of (v0, v1, v2), in double.
inline float plane_distance(Vec3f o, Vec3f d, const float* v0, const float* v1, const float* v2) {
  double e1[3], e2[3], w[3];
  for (int a = 0; a < 3; ++a) {
    e1[a] = double(v1[a]) - double(v0[a]);
    e2[a] = double(v2[a]) - double(v0[a]);
    w[a] = double(v0[a]) - double(o[a]);
  }
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double den = n[0] * double(d.x) + n[1] * double(d.y) + n[2] * double(d.z);
  return float((n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / den);  // +-inf or NaN when parallel: never in range
}

// Vertices as float[3] so the permuted components are plain indexed loads.
inline bool intersect_triangle(const WatertightRay& r, const float* v0, const float* v1, const float* v2, float tmin,
                               float tmax, TriangleHit& out) {
  const float o[3] = {r.o.x, r.o.y, r.o.z};
  const float az = v0[r.kz] - o[r.kz], bz = v1[r.kz] - o[r.kz], cz = v2[r.kz] - o[r.kz];
  const float ax = (v0[r.kx] - o[r.kx]) - r.sx * az, ay = (v0[r.ky] - o[r.ky]) - r.sy * az;
  const float bx = (v1[r.kx] - o[r.kx]) - r.sx * bz, by = (v1[r.ky] - o[r.ky]) - r.sy * bz;
  const float cx = (v2[r.kx] - o[r.kx]) - r.sx * cz, cy = (v2[r.ky] - o[r.ky]) - r.sy * cz;
  float u = cx * by - cy * bx;
  float v = ax * cy - ay * cx;
  float w = bx * ay - by * ax;
  if (u == 0.0f || v == 0.0f || w == 0.0f) {
    u = float(double(cx) * double(by) - double(cy) * double(bx));
    v = float(double(ax) * double(cy) - double(ay) * double(cx));
    w = float(double(bx) * double(ay) - double(by) * double(ax));
  }
  if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return false;
  const float det = u + v + w;
  if (det == 0.0f) return false;
  const float t = plane_distance(r.o, r.d, v0, v1, v2);
  if (!(t >= tmin && t <= tmax)) return false;
  const float inv_det = 1.0f / det;
  out = {t, v * inv_det, w * inv_det};
  return true;
}

inline bool intersect_triangle(const WatertightRay& r, Vec3f v0, Vec3f v1, Vec3f v2, float tmin, float tmax,
                               TriangleHit& out) {
  const float a[3] = {v0.x, v0.y, v0.z}, b[3] = {v1.x, v1.y, v1.z}, c[3] = {v2.x, v2.y, v2.z};
  return intersect_triangle(r, a, b, c, tmin, tmax, out);
}

}  // namespace kiln
