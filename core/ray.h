// Rays and the robust origin offset used by every spawned ray (shadow, reflection, refraction, bounce).
#pragma once
#include <bit>
#include <cstdint>

#include "core/vec.h"

namespace kiln {

struct Ray {
  Vec3f o;
  Vec3f d;
  float tmin = 0.0f;
  float tmax = kInfinity;
  Vec3f at(float t) const { return o + d * t; }
};

// Offsetting by a fixed epsilon breaks at large or tiny scene scales. Instead, move the origin by a fixed number
// of ulps along the geometric normal (scale-invariant far from the origin), with an absolute nudge only near the
// origin where ulps become denormal-small (after Waechter & Binder, Ray Tracing Gems ch. 6).
inline constexpr float kOffsetOriginRegion = 1.0f / 32.0f;   // below this |coordinate| use the absolute nudge
inline constexpr float kOffsetFloatScale = 1.0f / 65536.0f;  // absolute nudge near the origin
inline constexpr float kOffsetIntScale = 256.0f;             // ulps moved along the normal elsewhere

inline float offset_component(float p, float n) {
  const int32_t of = static_cast<int32_t>(kOffsetIntScale * n);
  const int32_t bits = std::bit_cast<int32_t>(p);
  const float pi = std::bit_cast<float>(bits + ((p < 0.0f) ? -of : of));
  return std::abs(p) < kOffsetOriginRegion ? p + kOffsetFloatScale * n : pi;
}

// p: hit point; ng: geometric normal (any length is fine up to unit); w: direction the new ray leaves in.
inline Vec3f offset_ray_origin(Vec3f p, Vec3f ng, Vec3f w) {
  const Vec3f n = dot(ng, w) < 0.0f ? -ng : ng;
  return {offset_component(p.x, n.x), offset_component(p.y, n.y), offset_component(p.z, n.z)};
}

// A ray leaving p (with geometric normal ng) towards w.
inline Ray spawn_ray(Vec3f p, Vec3f ng, Vec3f w) { return Ray{offset_ray_origin(p, ng, w), w, 0.0f, kInfinity}; }

// A shadow ray from p to target; stops just short of the target (target itself offset by its own normal when it
// lies on a surface).
inline constexpr float kShadowRayEndFraction = 1.0f - 1e-4f;
inline Ray spawn_ray_to(Vec3f p, Vec3f ng, Vec3f target) {
  const Vec3f o = offset_ray_origin(p, ng, target - p);
  return Ray{o, target - o, 0.0f, kShadowRayEndFraction};
}

}  // namespace kiln
