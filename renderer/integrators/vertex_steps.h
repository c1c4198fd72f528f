// The steps of a path vertex that Kiln's path tracer and the course's path tracer share, in the order their loops
// (pbrt-v4's PathIntegrator::Li in shape) take them: resolve the hit's material, orient it, then (each integrator's
// own rules: emission weights, light sampling, the course's Fresnel split and roulette) scatter into a sampled
// direction and, past some depth, play Kiln's unbiased roulette. The building blocks below them (direction sampling,
// one light sample, densities) are in renderer/integrators/path_vertex.h.
#pragma once
#include <algorithm>
#include <cmath>

#include "renderer/integrators/path_vertex.h"

namespace kiln {

// What a path carries from one vertex to the next.
struct PathState {
  Ray ray;
  Rgb beta{1.0f};  // throughput
  // Product of eta^2 over transmissions: roulette ignores the 1/eta^2 radiance scaling inside dense glass, which
  // cancels when the path leaves it (pbrt-v4's etaScale).
  float eta_scale = 1.0f;
  bool after_specular = true;  // the ray left a delta bounce (the camera counts as one): emitters count in full
  // What the camera sample sees, for the AOVs (null when not asked for), and the path's length before `ray`.
  VisibleSurface* visible = nullptr;
  float travelled = 0.0f;
};

// The path leaves si, which its ray found, along `next`.
inline void move_on(PathState& p, const SurfaceInteraction& si, const Ray& next) {
  if (p.visible && !p.visible->found) p.travelled += si.t * length(p.ray.d);
  p.ray = next;
}

// The number of bounces a path may take: max_depth, unlimited (< 0) still bounded by kMaxPathVertices.
inline int path_depth_limit(int max_depth) {
  return max_depth < 0 ? kMaxPathVertices : std::min(max_depth, kMaxPathVertices);
}

// The hit's material with its textures applied (`scratch` holds a textured copy), recorded for the AOVs when it is
// the first surface the camera sample sees. False when the path ends at the hit: an emitter without a material, or a
// replace_all texture, whose colour reaches L through the throughput.
inline bool resolve_material(const RenderContext& ctx, SurfaceInteraction& si, Material& scratch, const PathState& p,
                             Rgb& L) {
  if (!si.material) {
    see_resolved_surface(p.visible, si, p.ray, p.travelled, nullptr);
    return false;
  }
  if (Rgb unlit; apply_hit_textures(ctx, si, scratch, unlit)) {
    L += p.beta * unlit;
    see_resolved_surface(p.visible, si, p.ray, p.travelled, &unlit);
    return false;
  }
  see_resolved_surface(p.visible, si, p.ray, p.travelled, nullptr);
  return true;
}

// Normals turned to the side the path arrived from (wo). A path that leaves a dielectric is attenuated by what it
// crossed inside; oriented materials keep their outward normals (renderer/integrators/shading.h). Without
// dielectrics in the scene every surface is two-sided. Always inlined: called out of line, the path's throughput
// would live in memory across the call (1% more instructions on the default scene).
template <bool kDielectric>
[[gnu::always_inline]] inline void orient_at_vertex(SurfaceInteraction& si, Vec3f wo, PathState& p) {
  if constexpr (kDielectric) {
    if (exits_dielectric(si, p.ray.d)) p.beta *= si.material->transmittance(si.t * length(p.ray.d));
    orient_normals(si, wo);
  } else if (dot(wo, si.ng) < 0.0f) {
    si.ng = -si.ng;
    si.ns = -si.ns;
  }
}

// The path follows the sampled direction ds: its throughput takes f |cos| / pdf and its next ray leaves si on the side
// ds points to. False when the throughput vanished. The shading frame alone decides reflection and transmission, as
// in pbrt-v4: a direction the shading normal reflects but the geometric one does not goes through the surface (the
// course's rules refuse it: course_path_tracer.cpp).
inline bool scatter(PathState& p, const SurfaceInteraction& si, const Frame& frame, const DirectionSample& ds) {
  const Vec3f wi = frame.to_world(ds.wi_local);
  p.beta *= ds.f * (abs_cos_theta(ds.wi_local) / ds.pdf);
  if (p.beta.is_black() || !p.beta.is_finite()) return false;
  if (ds.transmission) p.eta_scale *= sqr(ds.eta);
  p.after_specular = ds.specular;
  move_on(p, si, spawn_ray(si.p, si.ng, wi, p.ray.time, si.extent));
  return true;
}

// The probability that Kiln's roulette lets a path with this throughput go on: min(1, √throughput), Cycles' rule. It
// ends paths later than the throughput itself would (pbrt-v4's rule): where walls are bright, the light a path still
// gathers after a few bounces is comparable to what it gathered before, and ending it early costs more variance than
// the time it saves (README, "Where the time goes"). Survivors carry √throughput <= 1: weights stay bounded.
inline float roulette_survival(float throughput) { return std::min(1.0f, std::sqrt(throughput)); }

// Kiln's unbiased throughput roulette at the vertex whose dimensions start at dim: the path goes on with probability
// roulette_survival(beta * eta_scale) and then carries the share of the paths that ended. False when it ends.
inline bool survives_roulette(PathState& p, uint32_t dim, Sampler& sampler) {
  const float survive = roulette_survival(p.beta.max_component() * p.eta_scale);
  sampler.set_dimension(dim + kRouletteDimension);
  if (sampler.next_float() >= survive) return false;
  p.beta *= 1.0f / survive;
  return true;
}

}  // namespace kiln
