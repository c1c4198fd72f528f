// Rays and the robust origin offset used by every spawned ray (shadow, reflection, refraction, bounce).
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>

#include "core/vec.h"

namespace kiln {

struct Ray {
  Vec3f o;
  Vec3f d;
  float tmin = 0.0f;
  float tmax = kInfinity;
  // Instant within the shutter interval [0, 1): where motion-blurred shapes are (0 for scenes without motion blur).
  // Every ray of a path carries the camera ray's time.
  float time = 0.0f;
  Vec3f at(float t) const { return o + d * t; }
};

// Offsetting by a fixed epsilon breaks at large or tiny scene scales, and so does any absolute nudge. The error of a
// computed hit point is a few ulps of its largest coordinate (it comes from vertices or a centre of that
// magnitude), so the origin moves along the geometric normal by 256 ulps of that coordinate: scale-invariant from
// 1e-8 to 1e8 (after Waechter & Binder, Ray Tracing Gems ch. 6, without their fixed nudge near the origin).
inline constexpr float kOffsetRelative = 0x1p-15f;       // 256 ulps = 2^8 * 2^-23 of the largest coordinate
inline constexpr float kOffsetMinMagnitude = 0x1p-100f;  // keeps the offset normal-range at the very origin

// p: hit point; ng: unit geometric normal; w: direction the new ray leaves in. extent: a magnitude larger than p's
// own whose ulps bound the error of p or of the accelerator's intersection with the surface (an instance hit is
// computed from object space through the instance transform, whose translation may dwarf p); 0 when p's own is.
inline Vec3f offset_ray_origin(Vec3f p, Vec3f ng, Vec3f w, float extent = 0.0f) {
  const Vec3f n = dot(ng, w) < 0.0f ? -ng : ng;
  const float m = std::max({max_component(abs(p)), extent, kOffsetMinMagnitude});
  // 2^floor(log2 m) * 2^-15: 256 ulps of m. The dominant normal component (>= 1/sqrt 3) then moves its coordinate
  // by >= 147 of its own ulps, so the origin lies strictly on w's side of the tangent plane.
  const float offset = std::bit_cast<float>(std::bit_cast<uint32_t>(m) & 0x7f800000u) * kOffsetRelative;
  return p + n * offset;
}

// A ray leaving p (with geometric normal ng) towards w, at the instant `time` of the path.
inline Ray spawn_ray(Vec3f p, Vec3f ng, Vec3f w, float time = 0.0f, float extent = 0.0f) {
  return Ray{offset_ray_origin(p, ng, w, extent), w, 0.0f, kInfinity, time};
}

// A shadow ray from p to target; stops just short of the target (target itself offset by its own normal when it
// lies on a surface).
inline constexpr float kShadowRayEndFraction = 1.0f - 1e-4f;
inline Ray spawn_ray_to(Vec3f p, Vec3f ng, Vec3f target, float time = 0.0f, float extent = 0.0f) {
  const Vec3f o = offset_ray_origin(p, ng, target - p, extent);
  return Ray{o, target - o, 0.0f, kShadowRayEndFraction, time};
}

}  // namespace kiln
