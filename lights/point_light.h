// Isotropic point light (CENG795 PointLight).
//   position   world-space location
//   intensity  radiant intensity I (RGB); irradiance on a surface facing it at distance d is I / d^2
// Cannot be hit by rays: its samples are delta with pdf 1.
#pragma once
#include "lights/light_sample.h"

namespace kiln {

class PointLight {
 public:
  PointLight(Vec3f position, Rgb intensity) : position_(position), intensity_(intensity) {}
  std::optional<LightSample> sample_li(const LightQuery& q, Vec2f u) const;
  float pdf_li(const LightQuery&, Vec3f, Vec3f, uint32_t) const { return 0.0f; }
  Rgb emitted(Vec3f, Vec3f) const { return {}; }
  float power() const;
  static constexpr bool kDelta = true;

  Vec3f position() const { return position_; }
  Rgb intensity() const { return intensity_; }

 private:
  Vec3f position_;
  Rgb intensity_;
};

}  // namespace kiln
