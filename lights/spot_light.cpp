#include "lights/spot_light.h"

#include "core/error.h"

namespace kiln {

SpotLight::SpotLight(Vec3f position, Vec3f direction, Rgb intensity, float coverage_deg, float falloff_deg,
                     bool smooth_step)
    : position_(position), intensity_(intensity), smooth_step_(smooth_step) {
  const float len = length(direction);
  if (!(len > 0.0f) || !std::isfinite(len)) throw Error("SpotLight: Direction has zero length");
  direction_ = direction / len;
  const float half_coverage = radians(std::clamp(coverage_deg, 0.0f, 360.0f)) * 0.5f;
  const float half_falloff = std::min(radians(std::clamp(falloff_deg, 0.0f, 360.0f)) * 0.5f, half_coverage);
  cos_coverage_ = std::cos(half_coverage);
  cos_falloff_ = std::cos(half_falloff);
}

float SpotLight::falloff(Vec3f w) const {
  const float cos_a = dot(w, direction_);
  if (cos_a >= cos_falloff_) return 1.0f;
  if (cos_a < cos_coverage_ || cos_falloff_ <= cos_coverage_) return 0.0f;
  const float s = (cos_a - cos_coverage_) / (cos_falloff_ - cos_coverage_);
  return smooth_step_ ? s * s * (3.0f - 2.0f * s) : sqr(sqr(s));
}

std::optional<LightSample> SpotLight::sample_li(const LightQuery& q, Vec2f) const {
  const Vec3f to_light = position_ - q.p;
  const float d2 = length_squared(to_light);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return std::nullopt;
  const float d = std::sqrt(d2);
  const Vec3f wi = to_light / d;
  const float scale = falloff(-wi);
  if (scale <= 0.0f) return std::nullopt;
  LightSample s;
  s.li = intensity_ * (scale / d2);
  s.wi = wi;
  s.p_light = position_;
  s.distance = d;
  s.pdf = 1.0f;
  s.delta = true;
  return s;
}

float SpotLight::power() const {
  // Exact flux: full intensity over the inner cap, and s^4 (or smoothstep(s)) with s linear in cos over the ring,
  // whose integral over cos is (cos_fall - cos_cov) / 5 (or / 2).
  const float cap = 1.0f - cos_falloff_;
  const float ring = (cos_falloff_ - cos_coverage_) / (smooth_step_ ? 2.0f : 5.0f);
  return 2.0f * kPi * intensity_.luminance() * (cap + ring);
}

}  // namespace kiln
