// Four triangles tested against one ray with SSE (x86-64 baseline): the BVH's leaf packets and their
// intersection, the SIMD twin of triangle_intersect.h.
#pragma once
#include <immintrin.h>

#include <cstdint>

#include "renderer/accel/triangle_intersect.h"

namespace kiln {

inline constexpr int kWidth = 4;

// Four triangles in SoA form for the SIMD watertight test. Unused lanes hold NaN vertices, which fail every
// comparison, so they never hit and never trigger the double-precision fallback.
struct alignas(16) Tri4 {
  float v[3][3][kWidth];  // [vertex][axis][lane]
  uint32_t slot[kWidth];  // index into Tree::refs
};

// Edge functions that round to exactly zero are recomputed in double (the Woop et al. fallback), lane by lane.
inline void refine_edge_functions(int lanes, const float* ax, const float* ay, const float* bx, const float* by,
                                  const float* cx, const float* cy, float* u, float* v, float* w) {
  for (int i = 0; i < kWidth; ++i) {
    if (!(lanes & (1 << i))) continue;
    u[i] = float(double(cx[i]) * double(by[i]) - double(cy[i]) * double(bx[i]));
    v[i] = float(double(ax[i]) * double(cy[i]) - double(ay[i]) * double(cx[i]));
    w[i] = float(double(bx[i]) * double(ay[i]) - double(by[i]) * double(ax[i]));
  }
}

// The watertight test of triangle_intersect.h on four triangles at once (same operations in the same order, so
// each lane's result is bit-identical to the scalar test). Returns the bit mask of lanes hit in [tmin, tmax] and
// their t and barycentrics (only the lanes of the mask are meaningful).
inline int intersect_tri4(const Tri4& p, const WatertightRay& w, float tmin, float tmax, float* t_out, float* b1_out,
                          float* b2_out) {
  const float o[3] = {w.o.x, w.o.y, w.o.z};
  const __m128 okx = _mm_set1_ps(o[w.kx]), oky = _mm_set1_ps(o[w.ky]), okz = _mm_set1_ps(o[w.kz]);
  const __m128 sx = _mm_set1_ps(w.sx), sy = _mm_set1_ps(w.sy);
  const __m128 az = _mm_sub_ps(_mm_load_ps(p.v[0][w.kz]), okz);
  const __m128 bz = _mm_sub_ps(_mm_load_ps(p.v[1][w.kz]), okz);
  const __m128 cz = _mm_sub_ps(_mm_load_ps(p.v[2][w.kz]), okz);
  const __m128 ax = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(p.v[0][w.kx]), okx), _mm_mul_ps(sx, az));
  const __m128 ay = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(p.v[0][w.ky]), oky), _mm_mul_ps(sy, az));
  const __m128 bx = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(p.v[1][w.kx]), okx), _mm_mul_ps(sx, bz));
  const __m128 by = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(p.v[1][w.ky]), oky), _mm_mul_ps(sy, bz));
  const __m128 cx = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(p.v[2][w.kx]), okx), _mm_mul_ps(sx, cz));
  const __m128 cy = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(p.v[2][w.ky]), oky), _mm_mul_ps(sy, cz));
  __m128 u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
  __m128 v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
  __m128 wv = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
  const __m128 zero = _mm_setzero_ps();
  const int zeros =
      _mm_movemask_ps(_mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(wv, zero)));
  if (zeros) [[unlikely]] {
    alignas(16) float fax[4], fay[4], fbx[4], fby[4], fcx[4], fcy[4], fu[4], fv[4], fw[4];
    _mm_store_ps(fax, ax), _mm_store_ps(fay, ay), _mm_store_ps(fbx, bx), _mm_store_ps(fby, by);
    _mm_store_ps(fcx, cx), _mm_store_ps(fcy, cy), _mm_store_ps(fu, u), _mm_store_ps(fv, v), _mm_store_ps(fw, wv);
    refine_edge_functions(zeros, fax, fay, fbx, fby, fcx, fcy, fu, fv, fw);
    u = _mm_load_ps(fu), v = _mm_load_ps(fv), wv = _mm_load_ps(fw);
  }
  const __m128 all_ge = _mm_and_ps(_mm_and_ps(_mm_cmpge_ps(u, zero), _mm_cmpge_ps(v, zero)), _mm_cmpge_ps(wv, zero));
  const __m128 all_le = _mm_and_ps(_mm_and_ps(_mm_cmple_ps(u, zero), _mm_cmple_ps(v, zero)), _mm_cmple_ps(wv, zero));
  const __m128 det = _mm_add_ps(_mm_add_ps(u, v), wv);
  const __m128 ok = _mm_and_ps(_mm_or_ps(all_ge, all_le), _mm_cmpneq_ps(det, zero));
  int mask = _mm_movemask_ps(ok);
  if (!mask) return 0;
  // The line crosses these triangles: their distance, in double (see triangle_intersect.h), decides the range.
  const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
  _mm_storeu_ps(b1_out, _mm_mul_ps(v, inv_det));
  _mm_storeu_ps(b2_out, _mm_mul_ps(wv, inv_det));
  for (int m = mask; m; m &= m - 1) {
    const int lane = __builtin_ctz(unsigned(m));
    const float a[3] = {p.v[0][0][lane], p.v[0][1][lane], p.v[0][2][lane]};
    const float b[3] = {p.v[1][0][lane], p.v[1][1][lane], p.v[1][2][lane]};
    const float c[3] = {p.v[2][0][lane], p.v[2][1][lane], p.v[2][2][lane]};
    const float t = plane_distance(w.o, w.d, a, b, c);
    t_out[lane] = t;
    if (!(t >= tmin && t <= tmax)) mask &= ~(1 << lane);
  }
  return mask;
}

}  // namespace kiln
