#include "lights/area_light.h"

#include "core/error.h"
#include "core/frame.h"

namespace kiln {

AreaLight::AreaLight(Vec3f corner, Vec3f edge1, Vec3f edge2, Rgb radiance)
    : corner_(corner), edge1_(edge1), edge2_(edge2), radiance_(radiance) {
  const Vec3f c = cross(edge1, edge2);
  area_ = length(c);
  if (!(area_ > 0.0f) || !std::isfinite(area_))
    throw Error("AreaLight: the light has zero area (Size 0 or parallel edge vectors)");
  normal_ = c / area_;
}

AreaLight AreaLight::square(Vec3f position, Vec3f normal, float size, Rgb radiance) {
  const float len = length(normal);
  if (!(len > 0.0f) || !std::isfinite(len)) throw Error("AreaLight: Normal has zero length");
  if (!(size > 0.0f) || !std::isfinite(size)) throw Error("AreaLight: Size must be positive");
  Vec3f s, t;
  coordinate_system(normal / len, s, t);
  const Vec3f e1 = s * size, e2 = t * size;
  return {position - (e1 + e2) * 0.5f, e1, e2, radiance};
}

std::optional<LightSample> AreaLight::sample_li(const LightQuery& q, Vec2f u) const {
  const Vec3f p = corner_ + edge1_ * u.x + edge2_ * u.y;
  const Vec3f to_light = p - q.p;
  const float d2 = length_squared(to_light);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return std::nullopt;
  const float d = std::sqrt(d2);
  const Vec3f wi = to_light / d;
  const float cos_l = absdot(normal_, wi);
  if (!(cos_l > 0.0f)) return std::nullopt;  // q lies in the light's plane
  LightSample s;
  s.li = radiance_;
  s.wi = wi;
  s.p_light = p;
  s.n_light = normal_;
  s.distance = d;
  s.pdf = d2 / (cos_l * area_);
  s.delta = true;
  return s;
}

float AreaLight::pdf_li(const LightQuery& q, Vec3f p_light, Vec3f, uint32_t) const {
  const Vec3f to_light = p_light - q.p;
  const float d2 = length_squared(to_light);
  if (!(d2 > 0.0f)) return 0.0f;
  const float cos_l = absdot(normal_, to_light) / std::sqrt(d2);
  return cos_l > 0.0f ? d2 / (cos_l * area_) : 0.0f;
}

// Two-sided Lambertian emitter: pi * A * L per side.
float AreaLight::power() const { return 2.0f * kPi * area_ * radiance_.luminance(); }

}  // namespace kiln
