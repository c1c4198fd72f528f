// Helpers shared by the material tests: directions at a given incidence, BRDF factories, sample wrappers.
#pragma once
#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <string>

#include "core/rng.h"
#include "materials/material.h"

namespace kiln::test {

// Unit direction with the given cos(theta) and azimuth phi (radians).
inline Vec3f direction_at(double cos_theta, double phi = 0.3) {
  const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return {float(s * std::cos(phi)), float(s * std::sin(phi)), float(cos_theta)};
}

inline std::string variant_name(PhongVariant v) {
  switch (v) {
    case PhongVariant::Original:
      return "Original";
    case PhongVariant::Modified:
      return "Modified";
    case PhongVariant::ModifiedNormalized:
      return "Normalized";
  }
  return "?";
}

// Wraps a surface BRDF as a Material so every test goes through one interface.
template <class Brdf>
Material surface_material(const Brdf& b) {
  Material m;
  m.surface = b;
  return m;
}

}  // namespace kiln::test

namespace kiln::test {

struct AlbedoEstimate {
  double mean = 0, stderr_ = 0;
};

// Directional albedo ∫ f cos dω_i by importance sampling with the material's own sampler (unbiased wherever the
// sampler's pdf covers the support of f, which holds for every surface BRDF here). Failed samples count 0.
inline AlbedoEstimate estimate_albedo(const Material& m, Vec3f wo, int n, uint64_t seed) {
  Rng rng(seed, 77);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const float uc = rng.next_float();
    const Vec2f u = rng.next_2d();
    double v = 0;
    if (const auto s = m.sample(wo, uc, u); s && !s->is_specular())
      v = double(s->f.average()) * std::abs(double(s->wi.z)) / double(s->pdf);
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

// ∫ f(w) dw over the upper hemisphere in (theta, phi), double precision: Simpson in theta, midpoint in phi
// (periodic, so spectrally accurate). Resolves lobes far narrower than integrate_sphere's cos-phi grid.
template <class F>
double integrate_upper_hemisphere(F&& f, int n_theta = 4000, int n_phi = 256) {
  constexpr double kPiD = 3.14159265358979323846;
  const double h = (kPiD / 2) / n_theta, dp = 2 * kPiD / n_phi;
  double total = 0;
  for (int i = 0; i <= n_theta; ++i) {
    const double th = i * h;
    const double wt = (i == 0 || i == n_theta) ? 1 : (i % 2 ? 4 : 2);
    double ring = 0;
    for (int j = 0; j < n_phi; ++j) {
      const double ph = (j + 0.5) * dp;
      ring += f(Vec3f(float(std::sin(th) * std::cos(ph)), float(std::sin(th) * std::sin(ph)), float(std::cos(th))));
    }
    total += wt * ring * dp * std::sin(th);
  }
  return total * h / 3;
}

// Simpson's rule on [a, b] with n (even) intervals, double precision.
template <class F>
double simpson(F&& f, double a, double b, int n = 20000) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
  return s * h / 3.0;
}

// Unpolarised Fresnel reflectance of a dielectric from index n_i into n_t, double precision (1 under total internal
// reflection); cos_i on the side of incidence.
inline double fresnel_dielectric_ref(double cos_i, double n_i, double n_t) {
  const double sin_t = n_i / n_t * std::sqrt(std::max(0.0, 1 - cos_i * cos_i));
  if (sin_t >= 1) return 1;
  const double cos_t = std::sqrt(1 - sin_t * sin_t);
  const double rs = (n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t);
  const double rp = (n_t * cos_i - n_i * cos_t) / (n_t * cos_i + n_i * cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// Unpolarised reflectance of a conductor of complex index n = eta + i k (relative to the incident side).
inline double fresnel_conductor_ref(double cos_i, std::complex<double> n) {
  const std::complex<double> cos_t = std::sqrt(1.0 - (1 - cos_i * cos_i) / (n * n));
  const std::complex<double> rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
  const std::complex<double> rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

}  // namespace kiln::test
