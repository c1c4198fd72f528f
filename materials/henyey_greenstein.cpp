#include "materials/henyey_greenstein.h"

#include "core/frame.h"

namespace kiln {
namespace {

// Below this |g| the inversion formula loses precision; such a medium is treated as isotropic (by p as well as by
// sample, so that the pdf stays exact), a change of at most 3 |g| in the phase function.
constexpr float kIsotropicG = 1e-3f;

float effective_g(float g) { return std::abs(g) < kIsotropicG ? 0.0f : g; }

// Phase function in terms of the cosine mu between the propagation directions (-wo and wi).
float hg(float mu, float g) {
  const float denom = 1.0f + g * g - 2.0f * g * mu;
  return kInv4Pi * (1.0f - g * g) / (denom * safe_sqrt(denom));
}

}  // namespace

float HenyeyGreenstein::p(Vec3f wo, Vec3f wi) const { return hg(-dot(wo, wi), effective_g(g)); }

std::optional<PhaseSample> HenyeyGreenstein::sample(Vec3f wo, Vec2f u) const {
  const float ge = effective_g(g);
  float mu;
  if (ge == 0.0f) {
    mu = 1.0f - 2.0f * u.x;
  } else {
    const float s = (1.0f - ge * ge) / (1.0f - ge + 2.0f * ge * u.x);
    mu = (1.0f + ge * ge - s * s) / (2.0f * ge);
  }
  mu = std::clamp(mu, -1.0f, 1.0f);
  const float sin_t = safe_sqrt(1.0f - mu * mu), phi = 2.0f * kPi * u.y;
  const Frame frame(-wo);
  const Vec3f wi = normalize(frame.to_world(Vec3f(sin_t * std::cos(phi), sin_t * std::sin(phi), mu)));
  const float pdf = p(wo, wi);
  if (!(pdf > 0.0f) || !std::isfinite(pdf)) return std::nullopt;
  return PhaseSample{wi, pdf, pdf};
}

}  // namespace kiln
