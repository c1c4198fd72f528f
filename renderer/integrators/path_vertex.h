// The pieces both path tracers (Kiln's and the course's) are built from: the sampler's per-vertex dimension layout,
// direction sampling by a chosen strategy with its pdf, one light sample at a vertex (next event estimation) and the
// light-selection density of an emitter that a sampled ray found.
#pragma once
#include <optional>

#include "renderer/integrators/aov.h"
#include "renderer/integrators/integrator.h"
#include "renderer/integrators/shading.h"
#include "renderer/world/ray_query.h"

namespace kiln {

// Sampler requests of one path vertex. Each vertex starts at its own fixed dimension whatever earlier vertices
// skipped, so that a given request is stratified across the samples of a pixel.
inline constexpr uint32_t kLightChoiceDimension = 0;    // which light (1D)
inline constexpr uint32_t kLightPointDimension = 1;     // where on it (2D)
inline constexpr uint32_t kLobeDimension = 2;           // which BSDF lobe (1D)
inline constexpr uint32_t kDirectionDimension = 3;      // which direction (2D)
inline constexpr uint32_t kRouletteDimension = 4;       // whether the path goes on (1D)
inline constexpr uint32_t kDimensionsPerVertex = 5;

inline uint32_t vertex_dimension(int depth) { return kFirstPathDimension + uint32_t(depth) * kDimensionsPerVertex; }

struct DirectionSample {
  Vec3f wi_local;
  Rgb f;
  float pdf = 0;
  bool specular = false;
  bool transmission = false;
  float eta = 1.0f;  // relative IOR crossed (transmission)
};

// The uniform and cosine warps cover the hemisphere of wo: they cannot produce the delta directions a surface lobe
// may return (the mirror reflection of a smooth coat) nor a rough dielectric's transmission. Such a surface is
// sampled by its BSDF whatever the strategy, so every strategy still converges to the same image.
inline DirectionSampling sampling_for(DirectionSampling directions, const Material& m) {
  if (directions == DirectionSampling::Brdf) return directions;
  return (m.surface_flags() & (kLobeSpecular | kLobeTransmission)) ? DirectionSampling::Brdf : directions;
}

// Probability of choosing the delta part; compiled out for scenes without delta materials.
template <bool kDelta>
float delta_prob(const Material& m, Vec3f wo_l) {
  if constexpr (kDelta) return m.delta_probability(wo_l);
  else return 0.0f;
}

// Solid-angle pdf with which `directions` would produce wi_l (for MIS weights). surface_only: the delta part is
// followed some other way, so the surface part is sampled alone.
template <bool kDelta>
float direction_pdf(DirectionSampling directions, const Material& m, Vec3f wo_l, Vec3f wi_l, bool surface_only) {
  directions = sampling_for(directions, m);
  const float keep = surface_only ? 1.0f : 1.0f - delta_prob<kDelta>(m, wo_l);
  switch (directions) {
    case DirectionSampling::Brdf:
      return surface_only ? m.pdf_surface(wo_l, wi_l) : m.pdf(wo_l, wi_l);
    case DirectionSampling::Cosine:
      return keep * cosine_hemisphere_pdf(wi_l.z);
    case DirectionSampling::Uniform:
      return wi_l.z > 0.0f ? keep * uniform_hemisphere_pdf() : 0.0f;
  }
  return 0.0f;
}

// Draws the lobe choice and the direction from the vertex's dimensions (the caller sets kLobeDimension).
template <bool kDelta>
[[gnu::always_inline]] inline std::optional<DirectionSample> sample_direction(DirectionSampling directions,
                                                                              const Material& m, Vec3f wo_l,
                                                                              Sampler& sampler, bool surface_only) {
  const float uc = sampler.next_float_if(m.reads_lobe_choice());
  const Vec2f u = sampler.next_2d();
  if (surface_only && !m.has_surface()) return std::nullopt;
  directions = sampling_for(directions, m);
  if (directions == DirectionSampling::Brdf) {
    auto bs = surface_only ? m.sample_surface(wo_l, uc, u) : m.sample(wo_l, uc, u);
    if (!bs || bs->pdf <= 0.0f) return std::nullopt;
    return DirectionSample{bs->wi, bs->f, bs->pdf, bs->is_specular(), bs->is_transmission(), bs->eta};
  }
  const float pd = surface_only ? 0.0f : delta_prob<kDelta>(m, wo_l);
  if (kDelta && uc < pd) {
    auto bs = m.sample_delta(wo_l, uc / pd, u);
    if (!bs || bs->pdf <= 0.0f) return std::nullopt;
    return DirectionSample{bs->wi, bs->f, bs->pdf * pd, true, bs->is_transmission(), bs->eta};
  }
  // Surface part through a BSDF-independent warp, in the hemisphere wo lies in.
  Vec3f wi = directions == DirectionSampling::Cosine ? sample_cosine_hemisphere(u) : sample_uniform_hemisphere(u);
  float pdf = directions == DirectionSampling::Cosine ? cosine_hemisphere_pdf(wi.z) : uniform_hemisphere_pdf();
  if (wo_l.z < 0.0f) wi.z = -wi.z;
  pdf *= (1.0f - pd);
  if (pdf <= 0.0f) return std::nullopt;
  return DirectionSample{wi, m.eval(wo_l, wi), pdf, false, false};
}

// Surfaces a camera sample looks through for its AOVs (renderer/film/visible_surface.h): nothing but delta lobes.
inline bool looked_through(const Material& m) {
  return !m.has_surface() || !(m.surface_flags() & (kLobeDiffuse | kLobeGlossy));
}

// Records si as what the camera sample sees, unless something was recorded already or nobody asked (visible null).
// travelled: the path's length before the ray that found si; albedo() is only evaluated for the record. si's
// shading normal must be final (textures, bump and normal maps applied).
template <typename Albedo>
void see_surface(VisibleSurface* visible, const SurfaceInteraction& si, const Ray& ray, float travelled,
                 Albedo&& albedo) {
  if (!visible || visible->found) return;
  const Rgb a = albedo();
  visible->albedo = Rgb(std::clamp(a.r, 0.0f, 1.0f), std::clamp(a.g, 0.0f, 1.0f), std::clamp(a.b, 0.0f, 1.0f));
  visible->n = dot(si.ns, ray.d) > 0.0f ? -si.ns : si.ns;
  visible->p = si.p;
  visible->z = travelled + si.t * length(ray.d);
  visible->found = true;
}

// The hit as the AOVs see it once its material is resolved: a material's reflectance colour, a replace_all texture's
// colour (unlit), white for an emitter without a material; mirrors and glass are looked through.
inline void see_resolved_surface(VisibleSurface* visible, const SurfaceInteraction& si, const Ray& ray,
                                 float travelled, const Rgb* unlit) {
  if (!visible || visible->found) return;
  if (unlit) see_surface(visible, si, ray, travelled, [&] { return *unlit; });
  else if (!si.material) see_surface(visible, si, ray, travelled, [] { return Rgb(1.0f); });
  else if (!looked_through(*si.material))
    see_surface(visible, si, ray, travelled, [&] { return material_albedo(*si.material); });
}

// One light sample at a surface vertex: the selector's light, a point on it, the shadow ray.
struct DirectLight {
  Rgb value;              // f * Li * |cos theta_i| / light_pdf
  float light_pdf = 0.0f;  // solid angle, including the light's selection probability
  Vec3f wi_local;
  bool delta = false;     // from a light that rays cannot hit: nothing else can find it, so no MIS
};

// Draws from kLightChoiceDimension and kLightPointDimension of the vertex starting at `dim`: the world's light
// sampler chooses a light (or one triangle of a mesh light), then a point on it. Empty when the light is occluded,
// faces away or the BSDF does not scatter towards it.
// time: the path's instant (the shadow ray's).
[[gnu::always_inline]] inline std::optional<DirectLight> sample_direct_light(const World& w, const SurfaceInteraction& si,
                                                                           const Frame& frame, Vec3f wo_l, uint32_t dim,
                                                                           float time, Sampler& sampler,
                                                                           RayCounters& c) {
  sampler.set_dimension(dim + kLightChoiceDimension);
  const LightQuery q{si.p, si.ns};
  const auto chosen = w.light_sampler.sample(q, sampler.next_float_if(w.light_sampler.chooses()));
  const Vec2f u = sampler.next_2d();
  if (!chosen) return std::nullopt;
  const auto ls = sample_li(w.lights[chosen->light], chosen->part, q, u);
  if (!ls || !(ls->pdf > 0.0f) || ls->li.is_black()) return std::nullopt;
  const Vec3f wi_l = frame.to_local(ls->wi);
  const Rgb f = si.material->eval(wo_l, wi_l);
  if (f.is_black() || query_occluded(w, spawn_ray_to(si.p, si.ng, ls->p_light, time, si.extent), c)) return std::nullopt;
  const float light_pdf = ls->pdf * chosen->pmf;
  return DirectLight{f * ls->li * (abs_cos_theta(wi_l) / light_pdf), light_pdf, wi_l, ls->delta};
}

// What a camera ray that leaves the scene sees besides the infinite lights: the background texture at its pixel
// (film, renderer/integrators/integrator.h) when the scene has one, else the background colour. Only camera rays: secondary rays
// that leave see the background colour or the environment, as without a texture.
inline Rgb camera_background(const World& w, Vec2f film) {
  if (!w.textures || w.textures->background() < 0) return w.background;
  return w.textures->background_value(film);
}

// Radiance that infinite lights send along a ray leaving the scene in direction d, each weighted by weight(light
// index, the density with which NEE from `from` would have chosen d).
// Infinite lights are constant (InfiniteLight) or an environment map (ImageInfiniteLight).
template <typename Weight>
Rgb escaped_radiance(const World& w, Vec3f d, const LightQuery& from, Weight&& weight) {
  Rgb le(0.0f);
  const Vec3f dir = normalize(d);
  for (const int i : w.infinite_lights) {
    const float pmf = w.light_sampler.pmf(from, uint32_t(i), kWholeLight);
    le += std::visit(
        [&](const auto& light) -> Rgb {
          using L = std::decay_t<decltype(light)>;
          if constexpr (std::is_same_v<L, InfiniteLight> || std::is_same_v<L, ImageInfiniteLight>) {
            const Rgb l = light.radiance(dir);
            return l.is_black() ? l : l * weight(light.pdf_direction(from, dir) * pmf);
          } else {
            return Rgb(0.0f);
          }
        },
        w.lights[size_t(i)]);
  }
  return le;
}

// Solid-angle density with which next event estimation from `from` would have chosen the point of light `light`
// that a sampled ray found at si (the sampler's choice of the light, or of the triangle holding si, times the
// density of the point given that choice).
inline float emitter_pdf(const World& w, int light, const LightQuery& from, const SurfaceInteraction& si) {
  const uint32_t part = w.light_sampler.part(uint32_t(light), si.prim);
  return pdf_li(w.lights[size_t(light)], part, from, si.p, si.ng, si.prim) *
         w.light_sampler.pmf(from, uint32_t(light), part);
}

}  // namespace kiln
