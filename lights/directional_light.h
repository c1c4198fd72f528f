// Directional light (CENG795 DirectionalLight): parallel light from infinitely far away.
//   direction     the way the light travels (normalised here); wi = -direction
//   irradiance    the file's "Radiance", used as the irradiance on a surface facing the light (spec ambiguity 2)
//   scene_radius  radius of a sphere bounding the scene: shadow-ray targets are placed 2 * scene_radius away so
//                 they lie outside every object, and the power estimate is pi * r^2 * lum(E)
// Cannot be hit by rays: its samples are delta with pdf 1.
#pragma once
#include "lights/light_sample.h"

namespace kiln {

class DirectionalLight {
 public:
  DirectionalLight(Vec3f direction, Rgb irradiance, float scene_radius);
  std::optional<LightSample> sample_li(const LightQuery& q, Vec2f u) const;
  float pdf_li(const LightQuery&, Vec3f, Vec3f, uint32_t) const { return 0.0f; }
  Rgb emitted(Vec3f, Vec3f) const { return {}; }
  float power() const;
  static constexpr bool kDelta = true;

  Vec3f direction() const { return direction_; }
  float scene_radius() const { return scene_radius_; }

 private:
  Vec3f direction_;
  Rgb irradiance_;
  float scene_radius_ = 1.0f;
};

}  // namespace kiln
