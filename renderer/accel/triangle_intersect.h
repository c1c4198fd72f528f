// Watertight ray-triangle intersection (Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2013).
// The ray is sheared so that it runs along +z through the origin; the test is then a 2-D edge-function test on
// the sheared vertices. Neighbouring triangles evaluate a shared edge with bit-identical inputs, so a ray can
// never slip between them; edge functions that round to exactly zero are recomputed in double precision.
#pragma once
#include <utility>

#include "core/ray.h"

namespace kiln {

// Per-ray constants: the axis permutation (kz = dominant direction axis) and the shear.
struct WatertightRay {
  Vec3f o;
  int kx = 0, ky = 1, kz = 2;
  float sx = 0, sy = 0, sz = 1;
};

inline WatertightRay make_watertight_ray(const Ray& ray) {
  WatertightRay w;
  w.o = ray.o;
  w.kz = max_dimension(abs(ray.d));
  w.kx = w.kz == 2 ? 0 : w.kz + 1;
  w.ky = w.kx == 2 ? 0 : w.kx + 1;
  if (ray.d[w.kz] < 0.0f) std::swap(w.kx, w.ky);  // keep the winding so the sign of det means the same side
  w.sx = ray.d[w.kx] / ray.d[w.kz];
  w.sy = ray.d[w.ky] / ray.d[w.kz];
  w.sz = 1.0f / ray.d[w.kz];
  return w;
}

struct TriangleHit {
  float t, b1, b2;  // barycentrics of vertices 1 and 2
};

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
  const float tdet = u * (r.sz * az) + v * (r.sz * bz) + w * (r.sz * cz);
  const float inv_det = 1.0f / det;
  const float t = tdet * inv_det;
  if (!(t >= tmin && t <= tmax)) return false;
  out = {t, v * inv_det, w * inv_det};
  return true;
}

inline bool intersect_triangle(const WatertightRay& r, Vec3f v0, Vec3f v1, Vec3f v2, float tmin, float tmax,
                               TriangleHit& out) {
  const float a[3] = {v0.x, v0.y, v0.z}, b[3] = {v1.x, v1.y, v1.z}, c[3] = {v2.x, v2.y, v2.z};
  return intersect_triangle(r, a, b, c, tmin, tmax, out);
}

}  // namespace kiln
