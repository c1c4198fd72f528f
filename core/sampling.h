// Sampling warps from [0,1)^2 to geometric domains, each with its exact pdf (pbrt-v4 util/sampling.h style).
#pragma once
#include <span>
#include <vector>

#include "core/frame.h"

namespace kiln {

// Uniform hemisphere around +z; pdf 1/(2 pi) per steradian.
inline Vec3f sample_uniform_hemisphere(Vec2f u) {
  const float z = u.x;
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_hemisphere_pdf() { return kInv2Pi; }

inline Vec3f sample_uniform_sphere(Vec2f u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = safe_sqrt(1.0f - z * z);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_sphere_pdf() { return kInv4Pi; }

// (cos a, sin a) for |a| <= pi/4 from their Taylor polynomials (degree 10 and 9: truncation below 3e-9, under half
// an ulp of float), without libm's range reduction: every cosine-weighted bounce goes through here. The coefficients
// are multiplied, never divided by: a division by a constant stays a division (11 cycles) in IEEE arithmetic.
inline Vec2f cos_sin_within_quarter_pi(float a) {
  const float a2 = a * a;
  const float c =
      1.0f + a2 * (-1.0f / 2 + a2 * (1.0f / 24 + a2 * (-1.0f / 720 + a2 * (1.0f / 40320 - a2 * (1.0f / 3628800)))));
  const float s = a * (1.0f + a2 * (-1.0f / 6 + a2 * (1.0f / 120 + a2 * (-1.0f / 5040 + a2 * (1.0f / 362880)))));
  return {c, s};
}

// Concentric (Shirley-Chiu) map to the unit disk, as a signed radius and a unit direction (the disk point is
// r * dir): the square's ring at max(|ox|, |oy|) = |r| goes to the circle of that radius, each of its four sides to
// a quarter of the circle. On the sides where |oy| >= |ox| the angle is pi/2 - a, whose cosine and sine are a's
// sine and cosine. The square is u's float grid (multiples of 2^-24 in [0, 1)) centred on 0: every u lands strictly
// inside the disk, so a cosine-weighted direction never lies on the horizon, where its density would be 0 (u = 0
// would map to the edge).
inline constexpr float kHalfUnitGridStep = 0x1p-24f;
struct ConcentricPoint {
  float r;
  Vec2f dir;
};
inline ConcentricPoint concentric_point(Vec2f u) {
  const float ox = 2.0f * u.x - 1.0f + kHalfUnitGridStep, oy = 2.0f * u.y - 1.0f + kHalfUnitGridStep;
  if (ox == 0.0f && oy == 0.0f) return {0.0f, {1.0f, 0.0f}};
  if (std::abs(ox) > std::abs(oy)) return {ox, cos_sin_within_quarter_pi((kPi / 4.0f) * (oy / ox))};
  const Vec2f cs = cos_sin_within_quarter_pi((kPi / 4.0f) * (ox / oy));
  return {oy, {cs.y, cs.x}};
}
inline Vec2f sample_uniform_disk_concentric(Vec2f u) {
  const ConcentricPoint c = concentric_point(u);
  return c.dir * c.r;
}

// Cosine-weighted hemisphere around +z (Malley's method); pdf cos(theta)/pi. z comes from the radius, not from
// x^2 + y^2, whose rounding could reach 1 inside the disk and put a sample on the horizon.
inline Vec3f sample_cosine_hemisphere(Vec2f u) {
  const ConcentricPoint c = concentric_point(u);
  return {c.dir.x * c.r, c.dir.y * c.r, safe_sqrt(1.0f - c.r * c.r)};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f; }

// Uniform over the cone of directions around +z with cos(theta) >= cos_max; pdf 1/(2 pi (1 - cos_max)).
// one_minus_cos_max is passed separately so tiny cones (far or small spheres) keep their precision.
inline Vec3f sample_uniform_cone(Vec2f u, float one_minus_cos_max) {
  const float one_minus_cos = u.x * one_minus_cos_max;
  const float cos_t = 1.0f - one_minus_cos;
  // sin^2 = (1 - cos)(1 + cos), which stays accurate when cos is close to 1.
  const float sin_t = safe_sqrt(one_minus_cos * (2.0f - one_minus_cos));
  const float phi = 2.0f * kPi * u.y;
  return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}
inline float uniform_cone_pdf(float one_minus_cos_max) { return 1.0f / (2.0f * kPi * one_minus_cos_max); }

// Uniform barycentrics on a triangle (square-root warp): returns (b1, b2), b0 = 1 - b1 - b2.
inline Vec2f sample_uniform_triangle(Vec2f u) {
  const float su = std::sqrt(u.x);
  return {1.0f - su, u.y * su};
}

// Discrete distribution over n weights, sampled by inverting the CDF (binary search); built once.
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(std::span<const float> weights);
  size_t size() const { return pmf_.size(); }
  double total() const { return total_; }
  // Index chosen with probability weight/total; u in [0,1). The remapped u (for reuse) goes to *u_remapped.
  size_t sample(float u, float* pmf = nullptr, float* u_remapped = nullptr) const;
  float pmf(size_t i) const { return i < pmf_.size() ? pmf_[i] : 0.0f; }

 private:
  std::vector<float> pmf_;
  std::vector<double> cdf_;  // cdf_[i] = sum of pmf_[0..i), size n+1
  double total_ = 0.0;
};

// Power heuristic (beta = 2) for multiple importance sampling.
// Written in terms of the ratio of the smaller to the larger pdf: squaring the pdfs themselves overflows to
// inf/inf = NaN above ~1e19 (grazing area-light pdfs) and underflows to 0/0 below ~1e-19.
inline float power_heuristic(float f_pdf, float g_pdf) {
  if (std::isinf(f_pdf)) return 1.0f;
  if (f_pdf >= g_pdf) {
    if (!(f_pdf > 0.0f)) return 0.0f;
    const float r = g_pdf / f_pdf;
    return 1.0f / (1.0f + r * r);
  }
  const float r = f_pdf / g_pdf;
  return (r * r) / (1.0f + r * r);
}

}  // namespace kiln
