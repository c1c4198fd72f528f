// Emissive sphere or ellipsoid (CENG795 LightSphere).
//   center, radius  the sphere in object space
//   to_world        object-to-world transform (identity for plain spheres; non-uniform scale makes an ellipsoid;
//                   affine only); the world surface is to_world(sphere(center, radius))
//   radiance        constant radiance L emitted outward only (the inside of the shell emits nothing)
// From outside, sample_li samples the cone of directions the sphere subtends from the OBJECT-space query point
// (uniform in object solid angle) and converts the density exactly to world solid angle. When the query point is
// inside or on the surface it falls back to sampling the surface uniformly in object-space area.
#pragma once
#include <array>

#include "core/bounds.h"
#include "core/transform.h"
#include "lights/light_sample.h"

namespace kiln {

// The density light samples of an ellipsoid are divided by. The CENG795 course renderer divides by the OBJECT-space
// cone pdf (spec §14.13), which is biased under non-uniform scale; its reference images need that. Kiln's own rules
// use the exact world-space density. Spheres (uniform scale) are exact either way.
enum class EllipsoidPdf { Exact, CourseObjectSpace };

class SphereLight {
 public:
  // Throws kiln::Error when radius is not positive or to_world is singular.
  SphereLight(Vec3f center, float radius, const Transform& to_world, Rgb radiance,
              EllipsoidPdf density = EllipsoidPdf::Exact);

  std::optional<LightSample> sample_li(const LightQuery& q, Vec2f u) const;
  // Density of sample_li towards p_light. From outside it depends only on the direction q -> p_light (0 when that
  // ray misses the light); from inside it is the converted area density at p_light.
  float pdf_li(const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim) const;
  // Uniform object-space area sampling converted to world solid angle (the inside fallback, usable from anywhere).
  // Points whose outward normal faces away from q emit nothing towards it and give no sample.
  std::optional<LightSample> sample_area(const LightQuery& q, Vec2f u) const;
  float pdf_area(const LightQuery& q, Vec3f p_light) const;
  // n: the outward surface normal at the emitting point.
  Rgb emitted(Vec3f n, Vec3f w) const { return dot(n, w) > 0.0f ? radiance_ : Rgb{}; }
  // pi * area * lum(L) for an outward Lambertian emitter.
  float power() const { return kPi * surface_area_ * radiance_.luminance(); }
  static constexpr bool kDelta = false;

  // Exact for spheres (including uniformly scaled ones); Knud Thomsen's approximation (error < ~1.1%) for
  // ellipsoids.
  float surface_area() const { return surface_area_; }
  // True when q is inside the surface or on it (within kOnSurfaceTolerance), where sample_li samples area.
  bool contains(Vec3f p) const;
  // World-space bounds of the (transformed) surface: exact for ellipsoids.
  Bounds3f world_bounds() const;
  Rgb radiance() const { return radiance_; }

 private:
  using Affine = std::array<double, 12>;  // row-major 3x4 [linear | translation]
  struct Local;                           // object-space view of a query point (sphere_light.cpp)
  Local to_local(Vec3f q) const;
  // World solid-angle density per object solid-angle density along the unit world direction wi.
  double solid_angle_scale(const std::array<double, 3>& wi) const;

  Vec3f center_;
  float radius_ = 1.0f;
  Rgb radiance_;
  Affine to_world_{}, to_object_{};
  double abs_det_ = 1.0;
  float surface_area_ = 0.0f;
  bool course_pdf_ = false;
};

}  // namespace kiln
