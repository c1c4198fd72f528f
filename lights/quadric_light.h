// Emissive pbrt-v4 disk, cylinder or partial sphere (core/quadric.h): a "diffuse" area light on a quadric.
//   quadric, to_world  the shape in its object space and its placement (affine; non-uniform scales allowed)
//   flip               the emitting side is opposite the natural normal (pbrt's ReverseOrientation exclusive-or a
//                      mirroring to_world; the accelerators report the same oriented normal)
//   radiance           constant radiance L, from the side of the oriented normal only, or from both (two_sided)
//   image              instead of L, an image over pbrt's (u, v) of the quadric (lights/emission_image.h);
//                      radiance() and power() then take its mean
// Samples are uniform in the shape's object-space area (Quadric::sample_area) and carry the exact world density:
// a surface element's area grows by J = |det M| |M^-T n| under the affine map M, so the world area density is
// 1 / (A_obj J) and the solid-angle density d^2 / (|cos theta_l| A_obj J). Points whose emitting side faces away
// from the query give no sample (and density 0 in pdf_li), as they send it no light.
#pragma once
#include <array>
#include <memory>

#include "core/quadric.h"
#include "core/transform.h"
#include "lights/emission_image.h"
#include "lights/light_sample.h"

namespace kiln {

class QuadricLight {
 public:
  // Throws kiln::Error when to_world is singular.
  QuadricLight(const Quadric& quadric, const Transform& to_world, bool flip, Rgb radiance, bool two_sided);
  QuadricLight(const Quadric& quadric, const Transform& to_world, bool flip,
               std::shared_ptr<const EmissionImage> image, bool two_sided);

  std::optional<LightSample> sample_li(const LightQuery& q, Vec2f u) const;
  float pdf_li(const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim) const;
  // n: the oriented geometric normal at the emitting point (Hit::ng of the quadric); at.hit_uv: its (u, v).
  Rgb emitted(Vec3f n, Vec3f w, const EmitterPoint& at = {}) const {
    if (!(two_sided_ || dot(n, w) > 0.0f)) return Rgb{};
    return image_ ? image_->radiance(at.hit_uv) : radiance_;
  }
  // pi * area * lum(L) per emitting side.
  float power() const { return kPi * world_area_ * radiance_.luminance() * (two_sided_ ? 2.0f : 1.0f); }
  static constexpr bool kDelta = false;

  // The world-space area: exact for similarity transforms, a fine quadrature of J otherwise.
  float area() const { return world_area_; }
  // What a light hierarchy bounds it by: the shape, its placement and which side emits.
  const Quadric& quadric() const { return quadric_; }
  const Transform& to_world() const { return to_world_; }
  bool flip() const { return flip_; }
  bool two_sided() const { return two_sided_; }
  // The constant radiance, or an emission image's mean.
  Rgb radiance() const { return radiance_; }

 private:
  struct SurfaceSample {
    Vec3f p, n;       // world point and unit oriented normal
    float pdf_area;   // world area density
  };
  SurfaceSample at_object_point(Vec3f p_obj) const;
  // Solid-angle density at q of a surface sample; 0 when it sends q no light.
  float solid_angle_pdf(const LightQuery& q, const SurfaceSample& s, Vec3f& wi, float& distance) const;

  Quadric quadric_;
  Transform to_world_;
  bool flip_ = false;
  Rgb radiance_;
  bool two_sided_ = false;
  float abs_det_ = 1.0f;
  float world_area_ = 0.0f;
  std::shared_ptr<const EmissionImage> image_;  // null: radiance_ everywhere
};

}  // namespace kiln
