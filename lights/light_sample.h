// The query and sample records every light shares (split out of light.h so each light's header can use them;
// light.h re-exports them, so code that includes light.h is unaffected).
#pragma once
#include <cstdint>
#include <optional>

#include "core/color.h"
#include "core/vec.h"

namespace kiln {

// The shading point a light is sampled for.
struct LightQuery {
  Vec3f p;
  Vec3f n;  // shading normal, or zero when unknown (e.g. inside a medium)
};

// Where a ray found an emitting surface, for lights whose radiance varies over it (an emission image): the
// accelerator's primitive and its (u, v) (barycentrics on triangles, the surface's own (u, v) on quadrics).
struct EmitterPoint {
  uint32_t prim = 0;
  Vec2f hit_uv;
};

struct LightSample {
  Rgb li;            // radiance arriving at the query point along wi (for delta lights: intensity / d^2 etc.)
  Vec3f wi;          // unit direction from the query point towards the light
  Vec3f p_light;     // point on the light (for shadow rays); far away along wi for directional lights
  Vec3f n_light;     // light surface normal at p_light (zero for point, spot and directional lights)
  float distance = kInfinity;  // |p_light - q.p|
  float pdf = 0;     // solid-angle pdf at the query point; 1 for point, spot and directional lights
  // The light cannot be hit by rays (point, spot, directional, and the course's invisible AreaLight), so a BSDF
  // sample can never find it: the integrator must not MIS-weight this sample. For the AreaLight pdf is still its
  // real solid-angle density; for the others it is 1.
  bool delta = false;
};

}  // namespace kiln
