#include "lights/directional_light.h"

#include "core/error.h"

namespace kiln {

namespace {
// An empty or degenerate scene has no meaningful radius; any positive distance puts the target outside it.
constexpr float kMinSceneRadius = 1.0f;
// Shadow-ray targets sit this many scene radii away, safely beyond the bounding sphere from any point inside it.
constexpr float kTargetDistanceInRadii = 2.0f;
}  // namespace

DirectionalLight::DirectionalLight(Vec3f direction, Rgb irradiance, float scene_radius) : irradiance_(irradiance) {
  const float len = length(direction);
  if (!(len > 0.0f) || !std::isfinite(len)) throw Error("DirectionalLight: Direction has zero length");
  direction_ = direction / len;
  scene_radius_ = (scene_radius > 0.0f && std::isfinite(scene_radius)) ? scene_radius : kMinSceneRadius;
}

std::optional<LightSample> DirectionalLight::sample_li(const LightQuery& q, Vec2f) const {
  LightSample s;
  s.li = irradiance_;
  s.wi = -direction_;
  s.distance = kTargetDistanceInRadii * scene_radius_;
  s.p_light = q.p + s.wi * s.distance;
  s.pdf = 1.0f;
  s.delta = true;
  return s;
}

float DirectionalLight::power() const { return kPi * sqr(scene_radius_) * irradiance_.luminance(); }

}  // namespace kiln
