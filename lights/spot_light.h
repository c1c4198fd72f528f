// Spot light (CENG795 SpotLight, spec section 3): a point light restricted to a cone around its direction.
//   position        world-space location
//   direction       axis of the cone (the way the light shines; normalised here)
//   intensity       radiant intensity I on the axis (RGB); li = I * falloff / d^2
//   coverage_deg    FULL cone angle outside which nothing is emitted
//   falloff_deg     FULL cone angle inside which the intensity is I
// The course files do not settle whether the angles are full or half angles (spec ambiguity 6); Kiln reads them
// as full apertures, i.e. compares the angle alpha between the axis and the direction to the point with angle/2.
// Between the two half-angles the intensity is scaled by s^4, s = (cos a - cos cov) / (cos fall - cos cov).
// A falloff wider than the coverage is clamped to the coverage (a hard-edged cone).
// With SpotFalloff::SmoothStep (pbrt-v4) the ring's scale is smoothstep(s) = s^2 (3 - 2 s) instead of s^4.
#pragma once
#include "lights/light_sample.h"

namespace kiln {

class SpotLight {
 public:
  SpotLight(Vec3f position, Vec3f direction, Rgb intensity, float coverage_deg, float falloff_deg,
            bool smooth_step = false);
  std::optional<LightSample> sample_li(const LightQuery& q, Vec2f u) const;
  float pdf_li(const LightQuery&, Vec3f, Vec3f, uint32_t) const { return 0.0f; }
  Rgb emitted(Vec3f, Vec3f) const { return {}; }
  float power() const;
  static constexpr bool kDelta = true;

  // Intensity scale (0..1) towards a unit direction w leaving the light.
  float falloff(Vec3f w) const;
  Vec3f position() const { return position_; }
  Vec3f direction() const { return direction_; }
  Rgb intensity() const { return intensity_; }
  // Cosines of the half-angles of the coverage cone (nothing outside) and of the full-intensity cone.
  float cos_coverage() const { return cos_coverage_; }
  float cos_falloff() const { return cos_falloff_; }

 private:
  Vec3f position_, direction_;
  Rgb intensity_;
  float cos_coverage_ = 0, cos_falloff_ = 1;
  bool smooth_step_ = false;
};

}  // namespace kiln
