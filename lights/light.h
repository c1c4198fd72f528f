// Light interface: every light type exposes sample_li / pdf_li / emitted (pbrt-v4 base/light.h style), behind one
// variant so the hot path has no virtual calls.
#pragma once
#include <optional>
#include <variant>

#include "core/color.h"
#include "core/vec.h"
#include "lights/area_light.h"
#include "lights/directional_light.h"
#include "lights/mesh_light.h"
#include "lights/point_light.h"
#include "lights/sphere_light.h"
#include "lights/spot_light.h"

namespace kiln {

// The shading point a light is sampled for.
struct LightQuery {
  Vec3f p;
  Vec3f n;  // shading normal, or zero when unknown (e.g. inside a medium)
};

struct LightSample {
  Rgb li;            // radiance arriving at the query point along wi (for delta lights: intensity / d^2 etc.)
  Vec3f wi;          // unit direction from the query point towards the light
  Vec3f p_light;     // point on the light (for shadow rays); far away along wi for directional lights
  Vec3f n_light;     // light surface normal at p_light (zero for delta lights)
  float distance = kInfinity;
  float pdf = 0;     // solid-angle pdf at the query point; 1 for delta lights
  bool delta = false;  // point, spot, directional: cannot be hit by rays
};

using Light = std::variant<PointLight, SpotLight, DirectionalLight, AreaLight, MeshLight, SphereLight>;

std::optional<LightSample> sample_li(const Light& light, const LightQuery& q, Vec2f u);
// Solid-angle pdf that sample_li would produce the point p_light (with surface normal n_light, on triangle
// prim for mesh lights) from q. 0 for delta lights.
float pdf_li(const Light& light, const LightQuery& q, Vec3f p_light, Vec3f n_light, uint32_t prim);
// Radiance leaving a point of an emitting surface with normal n towards direction w (w points away from it).
Rgb emitted(const Light& light, Vec3f n, Vec3f w);
// Total emitted power (flux) estimate used by the power-proportional selector.
float power(const Light& light);
bool is_delta(const Light& light);

}  // namespace kiln
