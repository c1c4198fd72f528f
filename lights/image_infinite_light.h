// Radiance arriving from every direction as a lat-long (equirectangular) HDR image on an infinitely distant sphere:
// the CENG795 SphericalDirectionalLight, an environment map in pbrt's terms.
//   image         linear RGB, row 0 at the top; negative and non-finite values count as 0
//   scene_radius  radius of a sphere bounding the scene (shadow-ray targets, the power estimate), as InfiniteLight
//   sampling      ImportanceSampled: Kiln's rule; UniformHemisphere: the course's rule (renderer/integrators/rules.h decides)
//
// Mapping (the course's): y is up; a direction (x, y, z) is the texel at u = (1 + atan2(x, -z) / pi) / 2,
// v = acos(y) / pi (theta from +y, v = 0 at the top row). Radiance is the texel's value (nearest): piecewise constant,
// so the importance-sampling density below is exactly proportional to luminance * sin(theta) per texel.
//
// ImportanceSampled (pbrt-v3's InfiniteAreaLight, pbrt-v4's ImageInfiniteLight on lat-long): a piecewise-constant
// 2-D distribution over (u, v) with texel weights luminance * sin(theta at the row's centre) (the sin keeps the
// squeezed rows near the poles from being over-sampled); a (u, v) density p becomes the solid-angle density
// p / (2 pi^2 sin theta). UniformHemisphere: wi uniform over the hemisphere of the query's normal, pdf 1 / (2 pi)
// (the format's "sample a random direction in the hemisphere"); the sphere, 1 / (4 pi), without a normal.
// Both: pdf_direction(q, d) is the density sample_li gives d, for the MIS weight of a ray that escapes.
#pragma once
#include <vector>

#include "core/image.h"
#include "core/sampling.h"
#include "lights/light_sample.h"

namespace kiln {

enum class EnvMapSampling { ImportanceSampled, UniformHemisphere };

class ImageInfiniteLight {
 public:
  // Throws kiln::Error for an empty image or a scene radius that is not positive.
  ImageInfiniteLight(Image image, float scene_radius, EnvMapSampling sampling = EnvMapSampling::ImportanceSampled);

  std::optional<LightSample> sample_li(const LightQuery& q, Vec2f u) const;
  float pdf_direction(const LightQuery& q, Vec3f wi) const;
  float pdf_li(const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim) const;
  // Radiance carried by a ray that escapes in the unit direction d.
  Rgb radiance(Vec3f d) const;
  // The light interface's emission towards w (a ray travelling along -w sees it).
  Rgb emitted(Vec3f, Vec3f w) const { return radiance(-w); }
  float power() const;
  static constexpr bool kDelta = false;

  EnvMapSampling sampling() const { return sampling_; }
  // The unit direction of lat-long coordinates (u, v) and back (u, v in [0, 1]).
  static Vec3f direction(float u, float v);
  static Vec2f lat_long(Vec3f d);

 private:
  int texel_x(float u) const;
  int texel_y(float v) const;
  float importance_pdf(Vec3f wi) const;

  Image image_;
  float scene_radius_ = 1.0f;
  EnvMapSampling sampling_;
  Distribution1D rows_;                 // marginal over rows
  std::vector<Distribution1D> columns_;  // per row: conditional over its texels
  double radiant_integral_ = 0.0;       // integral of luminance over the sphere (W / m^2 / sr * sr)
};

}  // namespace kiln
