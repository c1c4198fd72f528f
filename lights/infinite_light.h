// Constant radiance arriving from every direction (pbrt-v4's UniformInfiniteLight, a pbrt "infinite" light with a
// constant "L"): what a ray that leaves the scene sees.
//   radiance      L (RGB), the same in every direction
//   scene_radius  radius of a sphere bounding the scene: shadow-ray targets are placed 2 * scene_radius away along
//                 wi, outside every object; the power estimate is pbrt's 4 pi * pi r^2 * lum(L)
// sample_li draws wi cosine-weighted over the hemisphere of the query's normal (pdf cos / pi, zero below it), or
// uniformly over the sphere when the query has no normal (pdf 1 / 4 pi). Directions below the surface therefore
// have light pdf 0: an integrator that MIS-combines this with BSDF sampling gives those (transmitted) directions
// to the BSDF samples in full and stays unbiased.
// Escaped rays: radiance(d) is the L a ray leaving the scene in direction d carries; pdf_direction(q, d) is the
// density sample_li would give d, for the MIS weight of a BSDF-sampled ray that escapes.
#pragma once
#include "lights/light_sample.h"

namespace kiln {

class InfiniteLight {
 public:
  // Throws kiln::Error when the radiance is negative or not finite, or scene_radius is not positive.
  InfiniteLight(Rgb radiance, float scene_radius);

  std::optional<LightSample> sample_li(const LightQuery& q, Vec2f u) const;
  // Solid-angle density of sample_li producing the unit direction wi at q.
  float pdf_direction(const LightQuery& q, Vec3f wi) const;
  // The light interface's form: the direction is p_light - q.p (a point sample_li returned).
  float pdf_li(const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim) const;
  // Radiance carried by a ray that escapes in direction d.
  Rgb radiance(Vec3f) const { return radiance_; }
  // The light interface's emission: the same L whatever the (absent) surface normal.
  Rgb emitted(Vec3f, Vec3f) const { return radiance_; }
  float power() const;
  static constexpr bool kDelta = false;

  float scene_radius() const { return scene_radius_; }

 private:
  Rgb radiance_;
  float scene_radius_ = 1.0f;
};

}  // namespace kiln
