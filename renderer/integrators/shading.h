// Shared shading helpers for the integrators.
#pragma once
#include "core/frame.h"
#include "renderer/integrators/render_context.h"
#include "renderer/world/hit_textures.h"
#include "renderer/world/interaction.h"

namespace kiln {

// Beyond this many bounces a path always ends, even under unlimited-depth roulette (a white furnace with
// albedo 1 would otherwise never terminate).
inline constexpr int kMaxPathVertices = 1024;

// Textures of the hit (renderer/world/hit_textures.h): a textured hit shades with `scratch`, its material with
// the texel's k_d / k_s, and a bent shading normal; footprints are measured in the context's camera's pixels.
// Returns true when a replace_all texture gives the surface's colour outright in `unlit`. Untextured hits (every hit
// of an untextured scene) only test one integer.
inline bool apply_hit_textures(const RenderContext& ctx, SurfaceInteraction& si, Material& scratch, Rgb& unlit) {
  if (si.textures < 0) return false;
  return apply_textures(*ctx.world.textures, ctx.pixel_spread, si, scratch, unlit);
}

inline bool is_dielectric(const Material& m) { return std::holds_alternative<Dielectric>(m.delta); }

// Opaque surfaces are two-sided: normals are flipped to the side the ray arrived from. Oriented materials
// (dielectrics, smooth or rough) keep their outward orientation so that the local frame tells inside (wo.z < 0)
// from outside.
inline void orient_normals(SurfaceInteraction& si, Vec3f wo) {
  if (!si.material->oriented() && dot(wo, si.ng) < 0.0f) {
    si.ng = -si.ng;
    si.ns = -si.ns;
  }
}

// True when a ray that arrived along d has travelled inside the closed dielectric it now leaves.
inline bool exits_dielectric(const SurfaceInteraction& si, Vec3f d) {
  return si.material && si.material->oriented() && dot(d, si.ng) > 0.0f;
}

// Opaque surfaces only reflect: a light direction below the geometric surface would leak light through it.
inline bool valid_reflection_side(const SurfaceInteraction& si, Vec3f wo, Vec3f wi) {
  return dot(wo, si.ng) * dot(wi, si.ng) > 0.0f;
}

// The shading frame and the geometry must agree on whether wi reflects or transmits: where a smooth shading normal
// bends away from the geometric one, a direction can be above one surface and below the other, and following it
// would leak light through the surface (or shadow it from its own side).
inline bool consistent_sides(const SurfaceInteraction& si, Vec3f wo, Vec3f wi, Vec3f wo_l, Vec3f wi_l) {
  return (wo_l.z * wi_l.z > 0.0f) == (dot(wo, si.ng) * dot(wi, si.ng) > 0.0f);
}

}  // namespace kiln
