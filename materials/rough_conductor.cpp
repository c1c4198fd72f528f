#include "materials/rough_conductor.h"

namespace kiln {
namespace {

// The reflection half vector of two directions in the upper hemisphere; empty when they cancel.
std::optional<Vec3f> half_vector(Vec3f wo, Vec3f wi) {
  const Vec3f h = wo + wi;
  if (!(length_squared(h) > 0.0f)) return std::nullopt;
  return normalize(h);
}

}  // namespace

Rgb RoughConductor::eval(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f) || is_specular()) return Rgb(0.0f);
  const std::optional<Vec3f> wm = half_vector(wo, wi);
  if (!wm) return Rgb(0.0f);
  const Rgb F = fresnel_conductor(std::abs(dot(wo, *wm)), ior);
  return F * (distribution.d(*wm) * distribution.g(wo, wi) / (4.0f * wo.z * wi.z));
}

float RoughConductor::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f) || is_specular()) return 0.0f;
  const std::optional<Vec3f> wm = half_vector(wo, wi);
  if (!wm) return 0.0f;
  const float cos_om = dot(wo, *wm);
  if (!(cos_om > 0.0f)) return 0.0f;
  return distribution.visible_d(wo, *wm) / (4.0f * cos_om);
}

std::optional<BsdfSample> RoughConductor::sample(Vec3f wo, float /*uc*/, Vec2f u) const {
  if (!(wo.z > 0.0f)) return std::nullopt;
  if (is_specular()) {
    const Vec3f wi = reflect_z(wo);
    return BsdfSample{fresnel_conductor(wo.z, ior) / wi.z, wi, 1.0f, kLobeReflection | kLobeSpecular};
  }
  const Vec3f wm = distribution.sample_visible(wo, u);
  const Vec3f wi = reflect(wo, wm);
  if (!(wi.z > 0.0f)) return std::nullopt;
  // f and pdf from (wo, wi) exactly as eval() and pdf() compute them, so a sample always reports their values.
  const float p = pdf(wo, wi);
  if (!(p > 0.0f)) return std::nullopt;
  return BsdfSample{eval(wo, wi), wi, p, kLobeReflection | kLobeGlossy};
}

}  // namespace kiln
