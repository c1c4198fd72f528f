#include "materials/rough_dielectric.h"

#include "materials/fresnel.h"

namespace kiln {
namespace {

// The microfacet normal that maps wo to wi (Walter et al.'s generalised half vector), facing +z.
struct HalfVector {
  Vec3f wm;
  float etap;  // 1 for reflection, else eta of wi's side over eta of wo's side
  bool reflection;
};

std::optional<HalfVector> half_vector(Vec3f wo, Vec3f wi, float eta) {
  const float cos_o = wo.z, cos_i = wi.z;
  if (cos_o == 0.0f || cos_i == 0.0f) return std::nullopt;
  const bool reflection = cos_o * cos_i > 0.0f;
  const float etap = reflection ? 1.0f : (cos_o > 0.0f ? eta : 1.0f / eta);
  Vec3f wm = wi * etap + wo;
  if (!(length_squared(wm) > 0.0f) || !is_finite(wm)) return std::nullopt;
  wm = normalize(wm);
  if (wm.z < 0.0f) wm = -wm;
  // Microfacets seen from behind by either direction scatter nothing.
  if (dot(wm, wi) * cos_i < 0.0f || dot(wm, wo) * cos_o < 0.0f) return std::nullopt;
  return HalfVector{wm, etap, reflection};
}

// Lobe-selection probabilities restricted to `lobes`.
struct LobeChoice {
  float reflect, transmit;
  float sum() const { return reflect + transmit; }
};

LobeChoice lobe_choice(float R, uint32_t lobes) {
  return {(lobes & kLobeReflection) ? R : 0.0f, (lobes & kLobeTransmission) ? 1.0f - R : 0.0f};
}

// (wi . wm + wo . wm / etap)^2, the refraction Jacobian's denominator.
float transmission_denominator(Vec3f wo, Vec3f wi, const HalfVector& h) {
  return sqr(dot(wi, h.wm) + dot(wo, h.wm) / h.etap);
}

}  // namespace

uint32_t RoughDielectric::flags() const {
  const uint32_t sides = eta == 1.0f ? kLobeTransmission : (kLobeReflection | kLobeTransmission);
  return sides | (is_specular() ? kLobeSpecular : kLobeGlossy);
}

float RoughDielectric::f(Vec3f wo, Vec3f wi, Transport mode) const {
  if (is_specular()) return 0.0f;
  const std::optional<HalfVector> h = half_vector(wo, wi, eta);
  if (!h) return 0.0f;
  const float F = fresnel_dielectric(dot(wo, h->wm), eta);
  const float dg = distribution.d(h->wm) * distribution.g(wo, wi);
  if (h->reflection) return dg * F / std::abs(4.0f * wo.z * wi.z);
  const float denom = transmission_denominator(wo, wi, *h) * wi.z * wo.z;
  if (denom == 0.0f) return 0.0f;
  float ft = dg * (1.0f - F) * std::abs(dot(wi, h->wm) * dot(wo, h->wm) / denom);
  if (mode == Transport::Radiance) ft /= sqr(h->etap);
  return std::isfinite(ft) ? ft : 0.0f;
}

float RoughDielectric::pdf(Vec3f wo, Vec3f wi, Transport /*mode*/, uint32_t lobes) const {
  if (is_specular()) return 0.0f;
  const std::optional<HalfVector> h = half_vector(wo, wi, eta);
  if (!h) return 0.0f;
  const LobeChoice p = lobe_choice(fresnel_dielectric(dot(wo, h->wm), eta), lobes);
  if (!(p.sum() > 0.0f)) return 0.0f;
  const float visible = distribution.visible_d(wo, h->wm);
  float pdf = 0.0f;
  if (h->reflection) {
    pdf = visible / (4.0f * std::abs(dot(wo, h->wm))) * (p.reflect / p.sum());
  } else {
    const float denom = transmission_denominator(wo, wi, *h);
    if (denom == 0.0f) return 0.0f;
    pdf = visible * std::abs(dot(wi, h->wm)) / denom * (p.transmit / p.sum());
  }
  return std::isfinite(pdf) ? pdf : 0.0f;
}

std::optional<BsdfSample> RoughDielectric::sample(Vec3f wo, float uc, Vec2f u, Transport mode,
                                                  uint32_t lobes) const {
  if (wo.z == 0.0f || !is_finite(wo)) return std::nullopt;
  if (is_specular()) {
    const float R = fresnel_dielectric(wo.z, eta);
    const LobeChoice p = lobe_choice(R, lobes);
    if (!(p.sum() > 0.0f)) return std::nullopt;
    if (uc < p.reflect / p.sum()) {
      const Vec3f wi = reflect_z(wo);
      return BsdfSample{Rgb(R / std::abs(wi.z)), wi, p.reflect / p.sum(), kLobeReflection | kLobeSpecular};
    }
    const std::optional<Refraction> t = refract(wo, eta);
    if (!t || t->wt.z == 0.0f) return std::nullopt;
    float ft = (1.0f - R) / std::abs(t->wt.z);
    if (mode == Transport::Radiance) ft /= sqr(t->etap);
    return BsdfSample{Rgb(ft), t->wt, p.transmit / p.sum(), kLobeTransmission | kLobeSpecular, t->etap};
  }

  const Vec3f wm = distribution.sample_visible(wo, u);
  const LobeChoice p = lobe_choice(fresnel_dielectric(dot(wo, wm), eta), lobes);
  if (!(p.sum() > 0.0f)) return std::nullopt;
  Vec3f wi;
  uint32_t flags = kLobeGlossy;
  float etap = 1.0f;
  if (uc < p.reflect / p.sum()) {
    wi = reflect(wo, wm);
    if (!same_hemisphere(wo, wi)) return std::nullopt;
    flags |= kLobeReflection;
  } else {
    const std::optional<Refraction> t = refract(wo, wm, eta);
    if (!t || t->wt.z == 0.0f || same_hemisphere(wo, t->wt)) return std::nullopt;
    wi = t->wt;
    etap = t->etap;
    flags |= kLobeTransmission;
  }
  // f and pdf from (wo, wi) exactly as f() and pdf() compute them, so a sample always reports their values.
  const float pd = pdf(wo, wi, mode, lobes);
  if (!(pd > 0.0f)) return std::nullopt;
  return BsdfSample{Rgb(f(wo, wi, mode)), wi, pd, flags, etap};
}

}  // namespace kiln
