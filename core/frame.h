// Orthonormal shading frame: local z is the normal, so cos(theta) of a local direction is its z component.
#pragma once
#include "core/vec.h"

namespace kiln {

// Branchless orthonormal basis (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
inline void coordinate_system(Vec3f n, Vec3f& s, Vec3f& t) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  s = Vec3f(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  t = Vec3f(b, sign + n.y * n.y * a, -n.y);
}

struct Frame {
  Vec3f s, t, n;
  Frame() : s(1, 0, 0), t(0, 1, 0), n(0, 0, 1) {}
  explicit Frame(Vec3f normal) : n(normal) { coordinate_system(n, s, t); }
  Frame(Vec3f s_, Vec3f t_, Vec3f n_) : s(s_), t(t_), n(n_) {}
  Vec3f to_local(Vec3f v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3f to_world(Vec3f v) const { return s * v.x + t * v.y + n * v.z; }
};

// Local-frame trigonometry (w is a unit vector in a Frame).
inline float cos_theta(Vec3f w) { return w.z; }
inline float abs_cos_theta(Vec3f w) { return std::abs(w.z); }
inline float sin2_theta(Vec3f w) { return std::max(0.0f, 1.0f - w.z * w.z); }
inline bool same_hemisphere(Vec3f a, Vec3f b) { return a.z * b.z > 0.0f; }

}  // namespace kiln
