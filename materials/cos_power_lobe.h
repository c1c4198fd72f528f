// Cosine-power lobe around +z: pdf(w) = (n+1)/(2 pi) cos^n(theta) on the hemisphere cos(theta) > 0, 0 elsewhere.
// Used to sample Phong lobes (around the mirror direction) and Blinn half vectors (around the normal).
#pragma once
#include "core/frame.h"

namespace kiln {

// Inverting the CDF 1 - cos^(n+1) gives cos = u^(1/(n+1)); 1 - cos is computed through expm1 so that huge
// exponents (1e5) keep their tiny lobe width instead of rounding cos to exactly 1.
inline Vec3f sample_cos_power(Vec2f u, float n) {
  const float one_minus_cos = float(-std::expm1(std::log(double(u.x)) / (double(n) + 1.0)));
  const float cos_t = 1.0f - one_minus_cos;
  const float sin_t = safe_sqrt(one_minus_cos * (2.0f - one_minus_cos));
  const float phi = 2.0f * kPi * u.y;
  return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}

// Evaluated in double: for n near 1e5 the float rounding of cos would be amplified n times.
inline float cos_power_pdf(float cos_theta, float n) {
  if (!(cos_theta > 0.0f)) return 0.0f;
  const double c = std::min(double(cos_theta), 1.0);
  return float((double(n) + 1.0) * (0.5 / 3.14159265358979323846) * std::pow(c, double(n)));
}

// cos^n clamped to the lobe (0 for cos <= 0), in double for the same reason.
inline float cos_power(float cos_theta, float n) {
  if (!(cos_theta > 0.0f)) return 0.0f;
  return float(std::pow(std::min(double(cos_theta), 1.0), double(n)));
}

}  // namespace kiln
