// The course's direct-lighting ray tracer (spec §3-§5): ambient + every light sampled once with a shadow ray,
// emission of object lights seen directly, and deterministic mirror / dielectric / conductor recursion up to
// MaxRecursionDepth.
//
// Course conventions the hw1_2021 reference PNGs pin down (scienceTree: 3.06% of pixels off without them):
// - a dielectric hit from inside adds no ambient and no light samples, only its reflection / refraction;
// - refraction weighs 1 - F, without the 1/eta^2 radiance scaling (it cancels for a path that enters and
//   leaves a closed object, but not for paths that end inside, e.g. on the mirror floor the tree stands in);
// - every spawned ray (shadow, reflection, refraction) starts ShadowRayEpsilon along the geometric normal on
//   its side (CourseRaySettings::ray_epsilon; 0 falls back to Kiln's ulp-based offset).
#include "renderer/integrators/path_vertex.h"

namespace kiln {
namespace {

// A ray leaving si towards wi: the course's fixed offset along the normal, or Kiln's robust one.
// time: the path's instant (the camera ray's).
Ray spawn_course_ray(const SurfaceInteraction& si, Vec3f wi, float epsilon, float time) {
  if (!(epsilon > 0.0f)) return spawn_ray(si.p, si.ng, wi, time, si.extent);
  const Vec3f n = dot(si.ng, wi) < 0.0f ? -si.ng : si.ng;
  return Ray{si.p + n * epsilon, wi, 0.0f, kInfinity, time};
}

Ray spawn_course_shadow_ray(const SurfaceInteraction& si, Vec3f target, float epsilon, float time) {
  if (!(epsilon > 0.0f)) return spawn_ray_to(si.p, si.ng, target, time, si.extent);
  const Vec3f n = dot(si.ng, target - si.p) < 0.0f ? -si.ng : si.ng;
  const Vec3f o = si.p + n * epsilon;
  return Ray{o, target - o, 0.0f, kShadowRayEndFraction, time};
}

Rgb direct_from_lights(const World& w, const CourseRaySettings& s, const SurfaceInteraction& si,
                       const Frame& frame, Vec3f wo, float time, Sampler& sampler, RayCounters& c) {
  Rgb sum(0.0f);
  const Vec3f wo_l = frame.to_local(wo);
  for (const Light& light : w.lights) {
    const Vec2f u = sampler.next_2d();
    const auto ls = sample_li(light, LightQuery{si.p, si.ns}, u);
    if (!ls || ls->pdf <= 0.0f || ls->li.is_black()) continue;
    if (!valid_reflection_side(si, wo, ls->wi)) continue;
    const Vec3f wi_l = frame.to_local(ls->wi);
    const Rgb f = si.material->eval(wo_l, wi_l);
    if (f.is_black()) continue;
    const Ray shadow = spawn_course_shadow_ray(si, ls->p_light, s.ray_epsilon, time);
    if (query_occluded(w, shadow, c)) continue;
    sum += f * ls->li * (abs_cos_theta(wi_l) / ls->pdf);
  }
  return sum;
}

// film: the camera ray's pixel (renderer/integrators/integrator.h), for the background texture camera rays see.
// visible: the camera sample's record for the AOVs (or null); travelled: the length of the rays before `ray`.
Rgb trace_recursive(const RenderContext& ctx, const CourseRaySettings& s, const Ray& ray, Vec2f film, int depth,
                    Sampler& sampler, RayCounters& c, VisibleSurface* visible, float travelled) {
  const World& w = ctx.world;
  Hit hit;
  const bool found = depth == 0 && s.cull_camera_backfaces ? query_camera_culled(w, ray, hit, c)
                                                           : query_intersect(w, ray, hit, c, depth == 0);
  // Rays that leave see the environment (the map or a constant infinite light) in full: the ray tracer follows
  // only delta directions, which light sampling cannot produce. Reflected and refracted rays see the background
  // colour (the course's), camera rays the background texture where there is one.
  if (!found) {
    const Rgb background = depth == 0 ? camera_background(w, film) : w.background;
    return background + escaped_radiance(w, ray.d, LightQuery{}, [](float) { return 1.0f; });
  }
  SurfaceInteraction si = make_interaction(w, ray, hit);
  const Vec3f wo = -ray.d;
  Rgb L(0.0f);
  if (si.light >= 0) L += emitted_at(w, si, wo);
  if (!si.material) {
    see_resolved_surface(visible, si, ray, travelled, nullptr);
    return L;
  }
  Material textured;
  if (Rgb unlit; apply_hit_textures(ctx, si, textured, unlit)) {
    see_resolved_surface(visible, si, ray, travelled, &unlit);
    return L + unlit;
  }
  see_resolved_surface(visible, si, ray, travelled, nullptr);
  const Material& m = *si.material;
  const bool inside_dielectric = exits_dielectric(si, ray.d);
  const Rgb attenuation = inside_dielectric ? m.transmittance(hit.t * length(ray.d)) : Rgb(1.0f);
  orient_normals(si, wo);
  const Frame frame(si.ns);
  if (!inside_dielectric) {
    L += m.ambient * w.ambient;
    if (m.has_surface()) L += direct_from_lights(w, s, si, frame, wo, ray.time, sampler, c);
  }
  if (m.has_delta() && depth < s.max_depth) {
    const float next_travelled = visible && !visible->found ? travelled + hit.t * length(ray.d) : travelled;
    DeltaBranch branches[2];
    const int n = m.delta_branches(frame.to_local(wo), branches);
    for (int i = 0; i < n; ++i) {
      const auto wi_l = perturb(branches[i].wi, m.roughness, sampler.next_2d());
      if (!wi_l || branches[i].weight.is_black()) continue;
      const Vec3f wi = frame.to_world(*wi_l);
      // Undo the radiance scaling: the course weighs refraction by 1 - F alone.
      const Rgb weight = branches[i].transmission ? branches[i].weight * sqr(branches[i].etap) : branches[i].weight;
      L += weight * trace_recursive(ctx, s, spawn_course_ray(si, wi, s.ray_epsilon, ray.time), film, depth + 1,
                                    sampler, c, visible, next_travelled);
    }
  }
  return L * attenuation;
}

}  // namespace

Rgb integrate(const RenderContext& ctx, const CourseRaySettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
              RayCounters& c, VisibleSurface* visible) {
  return trace_recursive(ctx, s, ray, film, 0, sampler, c, visible, 0.0f);
}

}  // namespace kiln
