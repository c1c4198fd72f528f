// Course area light (CENG795 AreaLight): a parallelogram of constant radiance that shading points see but rays
// never hit (it is not part of the geometry).
//   square(position, normal, size, radiance): centred at position, perpendicular to normal, side size; its edges
//       come from coordinate_system(normal) (the course only says "an orthonormal basis from Normal", so the
//       square's in-plane rotation is an implementation choice)
//   parallelogram(corner, edge1, edge2, radiance): the 2018 form, points corner + a*edge1 + b*edge2, a,b in [0,1]
//       (Position read as a corner, as the 2018 student renderers do)
//   radiance  constant emitted radiance L, TWO-sided: emission toward w is L on either side (the course's
//             cos = |n.w| reading)
// Samples are uniform in area with the exact solid-angle pdf d^2 / (|cos theta_l| A). They are flagged delta
// ("cannot be hit by rays, so no MIS") although their pdf is a real density; emitted() is 0 for the same reason.
#pragma once
#include "lights/light_sample.h"

namespace kiln {

class AreaLight {
 public:
  AreaLight(Vec3f corner, Vec3f edge1, Vec3f edge2, Rgb radiance);
  static AreaLight square(Vec3f position, Vec3f normal, float size, Rgb radiance);
  static AreaLight parallelogram(Vec3f corner, Vec3f edge1, Vec3f edge2, Rgb radiance) {
    return {corner, edge1, edge2, radiance};
  }

  std::optional<LightSample> sample_li(const LightQuery& q, Vec2f u) const;
  // The density sample_li has at p_light (this light is never hit, but the value is exact and testable).
  float pdf_li(const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim) const;
  Rgb emitted(Vec3f, Vec3f) const { return {}; }
  float power() const;
  static constexpr bool kDelta = true;

  float area() const { return area_; }
  Vec3f normal() const { return normal_; }
  Vec3f corner() const { return corner_; }
  Vec3f edge1() const { return edge1_; }
  Vec3f edge2() const { return edge2_; }
  Rgb radiance() const { return radiance_; }

 private:
  Vec3f corner_, edge1_, edge2_, normal_;
  Rgb radiance_;
  float area_ = 0;
};

}  // namespace kiln
