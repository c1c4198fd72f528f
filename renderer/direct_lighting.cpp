// The course's direct-lighting ray tracer (spec §3-§5): ambient + every light sampled once with a shadow ray,
// emission of object lights seen directly, and deterministic mirror / dielectric / conductor recursion up to
// MaxRecursionDepth.
#include "renderer/integrator.h"
#include "renderer/ray_query.h"
#include "renderer/shading.h"

namespace kiln {
namespace {

Rgb direct_from_lights(const World& w, const SurfaceInteraction& si, const Frame& frame, Vec3f wo, Rng& rng,
                       RayCounters& c) {
  Rgb sum(0.0f);
  const Vec3f wo_l = frame.to_local(wo);
  for (const Light& light : w.lights) {
    const Vec2f u = rng.next_2d();
    const auto ls = sample_li(light, LightQuery{si.p, si.ns}, u);
    if (!ls || ls->pdf <= 0.0f || ls->li.is_black()) continue;
    if (!valid_reflection_side(si, wo, ls->wi)) continue;
    const Vec3f wi_l = frame.to_local(ls->wi);
    const Rgb f = si.material->eval(wo_l, wi_l);
    if (f.is_black()) continue;
    const Ray shadow = spawn_ray_to(si.p, si.ng, ls->p_light);
    if (query_occluded(w, shadow, c)) continue;
    sum += f * ls->li * (abs_cos_theta(wi_l) / ls->pdf);
  }
  return sum;
}

Rgb trace_recursive(const World& w, const IntegratorSettings& s, const Ray& ray, int depth, Rng& rng,
                    RayCounters& c) {
  Hit hit;
  if (!query_intersect(w, ray, hit, c, depth == 0 ? c.primary : c.indirect)) return w.background;
  SurfaceInteraction si = make_interaction(w, ray, hit);
  const Vec3f wo = -ray.d;
  Rgb L(0.0f);
  if (si.light >= 0) L += emitted(w.lights[size_t(si.light)], si.ng, wo);
  if (!si.material) return L;
  const Material& m = *si.material;
  const Rgb attenuation = exits_dielectric(si, ray.d) ? m.transmittance(hit.t * length(ray.d)) : Rgb(1.0f);
  orient_normals(si, wo);
  const Frame frame(si.ns);
  L += m.ambient * w.ambient;
  if (m.has_surface()) L += direct_from_lights(w, si, frame, wo, rng, c);
  if (m.has_delta() && depth < s.max_depth) {
    DeltaBranch branches[2];
    const int n = m.delta_branches(frame.to_local(wo), branches);
    for (int i = 0; i < n; ++i) {
      const auto wi_l = perturb(branches[i].wi, m.roughness, rng.next_2d());
      if (!wi_l || branches[i].weight.is_black()) continue;
      const Vec3f wi = frame.to_world(*wi_l);
      L += branches[i].weight * trace_recursive(w, s, spawn_ray(si.p, si.ng, wi), depth + 1, rng, c);
    }
  }
  return L * attenuation;
}

}  // namespace

Rgb trace_direct(const World& world, const IntegratorSettings& s, const Ray& ray, Rng& rng, RayCounters& c) {
  return trace_recursive(world, s, ray, 0, rng, c);
}

}  // namespace kiln
