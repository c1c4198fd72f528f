// A hit's texture footprint without ray differentials (pbrt-v4's Camera::Approximate_dp_dxy and
// SurfaceInteraction::ComputeDifferentials in shape): the camera's spread of ray position and direction per pixel
// step, turned to look at the hit, gives two neighbouring rays; where they cross the hit's tangent plane gives dp/dx
// and dp/dy; least squares on dp/du, dp/dv turns those into du/dx, dv/dx, du/dy, dv/dy. Used at every path vertex
// (the spread is the camera's, not the path's), only for textures filtered over a footprint
// (`Interpolation` trilinear / ewa).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/vec.h"

namespace kiln {

// The camera's rays near the film centre: what one pixel step along film x or y changes.
struct CameraSpread {
  Vec3f origin;              // the ray origin (the lens centre)
  Vec3f axis{0, 0, -1};      // unit direction of the ray through the film centre
  Vec3f dir_dx, dir_dy;      // change of a direction scaled to unit length along axis, per pixel step
  Vec3f pos_dx, pos_dy;      // change of the ray origin per pixel step (zero for a pinhole and a thin lens)
};

// The change of (u, v) per pixel step along film x and y.
struct UvFootprint {
  float dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
};

// dp/dx, dp/dy at surface point p with normal n (unit; either side): where the camera's spread, turned from its axis
// to the direction of p, crosses the plane through p. Zero for a ray that runs along the plane.
void approximate_dp_dxy(const CameraSpread& camera, Vec3f p, Vec3f n, Vec3f& dpdx, Vec3f& dpdy);

// du/dx ... dv/dy from dp/dx, dp/dy and the surface's dp/du, dp/dv (least squares: the projection of dp/dx on the
// span of dp/du, dp/dv); zero when dp/du and dp/dv are parallel.
UvFootprint uv_footprint(Vec3f dpdx, Vec3f dpdy, Vec3f dpdu, Vec3f dpdv);

// pbrt-v4 scales a hit's footprint by max(1/8, 1/sqrt(spp)): with many samples per pixel the pixel filter already
// averages the texture, so it is filtered over less than a pixel. Applied to pbrt-v4 textures only (the course
// textures' filtering is the course's).
inline constexpr float kMinPbrtFootprintScale = 0.125f;
inline float footprint_scale_for_spp(uint32_t samples_per_pixel) {
  return std::max(kMinPbrtFootprintScale, 1.0f / std::sqrt(float(std::max(samples_per_pixel, 1u))));
}

}  // namespace kiln
