#include "lights/point_light.h"

namespace kiln {

std::optional<LightSample> PointLight::sample_li(const LightQuery& q, Vec2f) const {
  const Vec3f to_light = position_ - q.p;
  const float d2 = length_squared(to_light);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return std::nullopt;
  const float d = std::sqrt(d2);
  LightSample s;
  s.li = intensity_ / d2;
  s.wi = to_light / d;
  s.p_light = position_;
  s.distance = d;
  s.pdf = 1.0f;
  s.delta = true;
  return s;
}

float PointLight::power() const { return 4.0f * kPi * intensity_.luminance(); }

}  // namespace kiln
