// Helpers shared by the light tests: Monte Carlo estimates with their standard error, and analytic irradiance.
#pragma once
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/rng.h"
#include "core/vec.h"
#include "lights/light.h"

namespace kiln::test {

inline constexpr double kPiD = 3.14159265358979323846;

struct Estimate {
  double mean = 0;
  double std_error = 0;  // standard error of the mean, from the sample variance
  int invalid = 0;       // non-finite sample values
};

// Mean of f(rng) over n samples.
template <class F>
Estimate estimate(F&& f, int n, uint64_t seed) {
  Rng rng(seed, 0x11647ull);
  double sum = 0, sum2 = 0;
  Estimate e;
  for (int i = 0; i < n; ++i) {
    const double v = f(rng);
    if (!std::isfinite(v)) {
      ++e.invalid;
      continue;
    }
    sum += v;
    sum2 += v * v;
  }
  e.mean = sum / n;
  const double var = std::max(0.0, sum2 / n - e.mean * e.mean);
  e.std_error = std::sqrt(var / (n - 1));
  return e;
}

// Irradiance estimate at q (normal q.n) from one light sample: li * max(0, cos) / pdf, 0 for failed samples.
// Reads the green channel: the tests use grey radiance.
template <class SampleFn>
double irradiance_sample(SampleFn&& sample, const LightQuery& q, Rng& rng) {
  const std::optional<LightSample> s = sample(q, rng.next_2d());
  if (!s) return 0.0;
  const double cos_i = std::max(0.0f, dot(q.n, s->wi));
  return double(s->li.g) * cos_i / double(s->pdf);
}

// Lambert's formula for the irradiance at p (normal n) from a uniform Lambertian polygon of radiance L that lies
// entirely above p's horizon: E = L/2 |sum_i beta_i cos gamma_i|, beta_i the angle edge i subtends at p and gamma_i
// the angle between n and the normal of the plane through p and that edge.
inline double polygon_irradiance(const std::vector<Vec3f>& verts, Vec3f p, Vec3f n, double radiance) {
  double sum = 0;
  const size_t k = verts.size();
  for (size_t i = 0; i < k; ++i) {
    const Vec3f a3 = verts[i] - p, b3 = verts[(i + 1) % k] - p;
    const double ax = a3.x, ay = a3.y, az = a3.z, bx = b3.x, by = b3.y, bz = b3.z;
    const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const double lc = std::sqrt(cx * cx + cy * cy + cz * cz);
    const double beta = std::atan2(lc, ax * bx + ay * by + az * bz);  // accurate for small and large angles
    if (lc > 0) sum += beta * (cx * n.x + cy * n.y + cz * n.z) / lc;
  }
  return 0.5 * radiance * std::abs(sum);
}

// Textbook form factor from a differential area to a parallel rectangle x by y with one corner straight above it
// at height h (independent of polygon_irradiance; used to check it).
inline double corner_rectangle_form_factor(double x, double y, double h) {
  const double X = x / h, Y = y / h;
  return (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
          Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
         (2.0 * kPiD);
}

// |err| must be within 4 standard errors plus a small relative slack for float rounding in the samplers.
inline constexpr double kSigmas = 4.0;
inline constexpr double kRoundingSlack = 1e-5;
inline bool within_error(const Estimate& e, double expected) {
  return std::abs(e.mean - expected) <= kSigmas * e.std_error + kRoundingSlack * std::abs(expected);
}

}  // namespace kiln::test
