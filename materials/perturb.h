// Course glossy reflection (spec §5 Roughness, Shirley's recipe): a delta direction r becomes
// normalize(r + roughness (xi1 a + xi2 b)) with (a, b) an orthonormal basis perpendicular to r and
// xi = u - 0.5 uniform in [-0.5, 0.5]^2. The result has no evaluable pdf, so samples stay specular-flagged.
#pragma once
#include <optional>

#include "core/frame.h"

namespace kiln {

// Empty when the perturbed direction crosses the surface plane (z changes sign; such rays are dropped, spec
// §14.12) or degenerates.
inline std::optional<Vec3f> perturb(Vec3f r, float roughness, Vec2f u) {
  if (!(roughness > 0.0f)) return r;
  Vec3f a, b;
  coordinate_system(r, a, b);
  const Vec3f q = r + (a * (u.x - 0.5f) + b * (u.y - 0.5f)) * roughness;
  const float len = length(q);
  if (!(len > 0.0f) || !std::isfinite(len)) return std::nullopt;
  const Vec3f p = q / len;
  if (!(p.z * r.z > 0.0f)) return std::nullopt;
  return p;
}

}  // namespace kiln
