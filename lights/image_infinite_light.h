// Radiance arriving from every direction as an HDR image on an infinitely distant sphere: the CENG795
// SphericalDirectionalLight and pbrt-v4's image "infinite" light (an environment map).
//   image         linear RGB, row 0 at the top; negative and non-finite values count as 0
//   scene_radius  radius of a sphere bounding the scene (shadow-ray targets, the power estimate), as InfiniteLight
//   sampling      ImportanceSampled: Kiln's rule; UniformHemisphere: the course's rule (renderer/integrators/rules.h decides)
//   placement     the image's layout and where its frame sits in the world
//
// Layouts, in the map's own frame (u to the right, v down the image, both in [0, 1]):
//   LatLong    (the course's) y is up; a direction (x, y, z) is the texel at u = (1 + atan2(x, -z) / pi) / 2,
//              v = acos(y) / pi (theta from +y, v = 0 at the top row).
//   EqualArea  (pbrt-v4's) Clarberg's octahedral equal-area square (core/equal_area.h): the centre is +z; lookups
//              beyond the square's edges fold back with the octahedral wrap. Square images only.
// The world direction of a map direction m is normalize(L m), L the linear part of placement.light_to_world (a
// rotation in practice; any invertible map works: the density below carries its exact solid-angle Jacobian
// 1 / (|det L| |L^-1 w|^3)).
//
// Radiance is the texel's value (nearest), so the map is piecewise constant and the importance-sampling density is
// exactly proportional to luminance per texel. ImportanceSampled: a piecewise-constant 2-D distribution over (u, v)
// with texel weights luminance * sin(theta at the row's centre) for LatLong (the sin keeps the squeezed rows near
// the poles from being over-sampled; a (u, v) density p is the solid-angle density p / (2 pi^2 sin theta)) and
// luminance alone for EqualArea (the map's Jacobian is the constant 4 pi: p / (4 pi)). UniformHemisphere: wi
// uniform over the hemisphere of the query's normal, pdf 1 / (2 pi) (the format's "sample a random direction in the
// hemisphere"); the sphere, 1 / (4 pi), without a normal. Both: pdf_direction(q, d) is the density sample_li gives
// d, for the MIS weight of a ray that escapes.
#pragma once
#include <array>
#include <vector>

#include "core/image.h"
#include "core/sampling.h"
#include "core/transform.h"
#include "lights/light_sample.h"

namespace kiln {

enum class EnvMapSampling { ImportanceSampled, UniformHemisphere };
enum class EnvMapLayout { LatLong, EqualArea };

struct EnvMapPlacement {
  EnvMapLayout layout = EnvMapLayout::LatLong;
  Transform light_to_world;  // only its linear part is used
};

class ImageInfiniteLight {
 public:
  // Throws kiln::Error for an empty image, an EqualArea image that is not square, a singular placement or a scene
  // radius that is not positive.
  ImageInfiniteLight(Image image, float scene_radius, EnvMapSampling sampling = EnvMapSampling::ImportanceSampled,
                     const EnvMapPlacement& placement = {});

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
  EnvMapLayout layout() const { return layout_; }
  // The unit direction of lat-long coordinates (u, v) and back (u, v in [0, 1]), in the map's frame.
  static Vec3f direction(float u, float v);
  static Vec2f lat_long(Vec3f d);
  // The unit direction, in the map's frame, of map coordinates (u, v) in this light's layout, and back.
  Vec3f map_direction(Vec2f uv) const;
  Vec2f map_coordinates(Vec3f d) const;
  // World <-> map frame (unit directions in, unit directions out).
  Vec3f to_world(Vec3f m) const;
  Vec3f to_map(Vec3f w) const;

 private:
  using Mat3 = std::array<float, 9>;  // row-major
  struct Texel {
    int x, y;
  };
  Texel texel(Vec2f uv) const;
  // Solid-angle density (in the map's frame) of a (u, v) density p_uv at the map direction m.
  float solid_angle_density(float p_uv, Vec3f m) const;
  // Density of importance sampling at the world direction wi.
  float importance_pdf(Vec3f wi) const;
  // Factor from map-frame to world solid-angle density at the world direction wi (1 when unplaced).
  float placement_jacobian(Vec3f wi) const;

  Image image_;
  float scene_radius_ = 1.0f;
  EnvMapSampling sampling_;
  EnvMapLayout layout_ = EnvMapLayout::LatLong;
  bool placed_ = false;  // light_to_world is not the identity
  Mat3 to_world_{}, to_map_{};
  float abs_det_ = 1.0f;
  Distribution1D rows_;                 // marginal over rows
  std::vector<Distribution1D> columns_;  // per row: conditional over its texels
  double radiant_integral_ = 0.0;       // integral of luminance over the sphere (W / m^2 / sr * sr)
};

}  // namespace kiln
