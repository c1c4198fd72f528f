#include "materials/fresnel.h"

#include <complex>

namespace kiln {

float fresnel_dielectric(float cos_theta_o, float eta) {
  if (eta == 1.0f) return 0.0f;  // index-matched: no interface (rounding would leave a ~1e-15 reflection)
  float cos_i = std::clamp(cos_theta_o, -1.0f, 1.0f);
  if (cos_i < 0.0f) {  // light arrives from inside: swap the media
    eta = 1.0f / eta;
    cos_i = -cos_i;
  }
  const float sin2_i = 1.0f - cos_i * cos_i;
  const float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = safe_sqrt(1.0f - sin2_t);
  const float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const float r = 0.5f * (r_parl * r_parl + r_perp * r_perp);
  return std::clamp(r, 0.0f, 1.0f);
}

float fresnel_conductor(float cos_theta_o, float eta, float kappa) {
  using C = std::complex<double>;
  const C n(eta, kappa);
  if (std::norm(n) == 0.0) return 1.0f;
  const double cos_i = std::clamp(double(std::abs(cos_theta_o)), 0.0, 1.0);
  const double sin2_i = 1.0 - cos_i * cos_i;
  const C sin2_t = sin2_i / (n * n);
  const C cos_t = std::sqrt(1.0 - sin2_t);
  const C r_parl = (n * cos_i - cos_t) / (n * cos_i + cos_t);
  const C r_perp = (cos_i - n * cos_t) / (cos_i + n * cos_t);
  const double r = 0.5 * (std::norm(r_parl) + std::norm(r_perp));
  return std::isfinite(r) ? float(std::clamp(r, 0.0, 1.0)) : 1.0f;
}

Rgb fresnel_conductor(float cos_theta_o, const RgbComplexIor& ior) {
  Rgb r;
  for (int c = 0; c < 3; ++c) r[c] = fresnel_conductor(cos_theta_o, ior.eta[c], ior.k[c]);
  return r;
}

float fresnel_r0(float eta, float kappa) {
  const float num = sqr(eta - 1.0f) + kappa * kappa;
  const float den = sqr(eta + 1.0f) + kappa * kappa;
  return den > 0.0f ? std::clamp(num / den, 0.0f, 1.0f) : 1.0f;
}

float fresnel_schlick(float cos_theta, float r0) {
  const float m = 1.0f - std::clamp(cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return r0 + (1.0f - r0) * (m2 * m2 * m);
}

std::optional<Refraction> refract(Vec3f wo, float eta) {
  float cos_i = wo.z;
  float etap = eta;
  float nz = 1.0f;  // normal on the side of wo
  if (cos_i < 0.0f) {
    etap = 1.0f / eta;
    cos_i = -cos_i;
    nz = -1.0f;
  }
  if (!(cos_i > 0.0f)) return std::nullopt;
  const float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
  const float sin2_t = sin2_i / (etap * etap);
  if (sin2_t >= 1.0f) return std::nullopt;
  const float cos_t = safe_sqrt(1.0f - sin2_t);
  // wt = -wo / etap + (cos_i / etap - cos_t) n, whose normal component simplifies to -cos_t n.
  const Vec3f wt = normalize(Vec3f(-wo.x / etap, -wo.y / etap, -nz * cos_t));
  return Refraction{wt, etap};
}

std::optional<Refraction> refract(Vec3f wo, Vec3f n, float eta) {
  float cos_i = dot(wo, n);
  float etap = eta;
  if (cos_i < 0.0f) {  // wo on the inside of the facet
    etap = 1.0f / eta;
    cos_i = -cos_i;
    n = -n;
  }
  if (!(cos_i > 0.0f)) return std::nullopt;
  const float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
  const float sin2_t = sin2_i / (etap * etap);
  if (sin2_t >= 1.0f) return std::nullopt;
  const float cos_t = safe_sqrt(1.0f - sin2_t);
  const Vec3f wt = normalize(-wo / etap + (cos_i / etap - cos_t) * n);
  return Refraction{wt, etap};
}

}  // namespace kiln
