// Kiln's path tracer (pbrt-v4's PathIntegrator::Li in shape): at every vertex, emission found by the sampled ray
// (MIS-weighted against next event estimation), one light sample (MIS-weighted against direction sampling), one
// sampled direction, unbiased throughput roulette after rr_min_depth bounces, at most max_depth bounces.
//
// Strategies: direction sampling by the BSDF, cosine or uniform hemisphere (delta lobes are always sampled); NEE off
// (light is found only by hitting emitters), NEE alone (emitters found by sampled rays are skipped, except from the
// camera and after delta bounces, where NEE could not reach them) or NEE with MIS. All converge to the same image.
#include "renderer/integrators/vertex_steps.h"

namespace kiln {
namespace {

// Weight of emission that a sampled ray found, against NEE having sampled the same point.
float emission_weight(const PathSettings& s, bool use_nee, bool after_specular, float direction_pdf, float light_pdf) {
  if (after_specular || !use_nee) return 1.0f;
  return s.mis ? power_heuristic(direction_pdf, light_pdf) : 0.0f;
}

// Specialised on the scene's feature mask (Cycles-style): without delta materials no delta probabilities are asked
// for, without dielectrics no media are tracked, with only world-space meshes the shape dispatch is compiled out.
template <bool kDelta, bool kDielectric, bool kMeshesOnly>
Rgb kiln_path(const RenderContext& ctx, const PathSettings& s, const Ray& camera_ray, Vec2f film, Sampler& sampler,
              RayCounters& c, VisibleSurface* visible) {
  const World& w = ctx.world;
  const bool use_nee = s.nee && !w.lights.empty();
  const int max_depth = path_depth_limit(s.max_depth);
  PathState p{camera_ray};
  p.visible = visible;
  Rgb L(0.0f);
  float prev_pdf = 0.0f;  // the density of the direction that found the vertex, and the vertex it left (MIS)
  LightQuery prev{};
  Material textured;  // the material of the current vertex when it is textured

  for (int depth = 0;; ++depth) {
    Hit hit;
    if (!query_intersect(w, p.ray, hit, c, depth == 0)) {
      if (depth == 0) L += p.beta * camera_background(w, film);
      L += p.beta * escaped_radiance(w, p.ray.d, prev, [&](float light_pdf) {
             return emission_weight(s, use_nee, p.after_specular, prev_pdf, light_pdf);
           });
      break;
    }
    SurfaceInteraction si = make_interaction<kMeshesOnly>(w, p.ray, hit);
    const Vec3f wo = -p.ray.d;
    if (si.light >= 0) {
      const Rgb le = emitted_at(w, si, wo);
      if (!le.is_black()) {
        const float light_pdf = p.after_specular || !s.mis ? 0.0f : emitter_pdf(w, si.light, prev, si);
        L += p.beta * le * emission_weight(s, use_nee, p.after_specular, prev_pdf, light_pdf);
      }
    }
    if (!resolve_material(ctx, si, textured, p, L) || depth >= max_depth) break;
    orient_at_vertex<kDielectric>(si, wo, p);
    const Material& m = *si.material;
    const Frame frame(si.ns);
    const Vec3f wo_l = frame.to_local(wo);
    const uint32_t dim = vertex_dimension(depth);

    if (use_nee && m.has_surface()) {
      if (const auto dl = sample_direct_light(w, si, frame, wo_l, dim, p.ray.time, sampler, c)) {
        const float weight =
            s.mis && !dl->delta
                ? power_heuristic(dl->light_pdf, direction_pdf<kDelta>(s.directions, m, wo_l, dl->wi_local, false))
                : 1.0f;
        L += p.beta * dl->value * weight;
      }
    }

    sampler.set_dimension(dim + kLobeDimension);
    const auto ds = sample_direction<kDelta>(s.directions, m, wo_l, sampler, false);
    if (!ds || !scatter(p, si, frame, *ds)) break;
    prev_pdf = ds->pdf;
    prev = LightQuery{si.p, si.ns};
    if (s.russian_roulette && depth >= s.rr_min_depth && !survives_roulette(p, dim, sampler)) break;
  }
  return L;
}

}  // namespace

Rgb integrate(const RenderContext& ctx, const PathSettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
              RayCounters& c, VisibleSurface* visible) {
  return dispatch_on_features(ctx.settings.features, [&]<bool kDelta, bool kDielectric, bool kMeshesOnly>() {
    return kiln_path<kDelta, kDielectric, kMeshesOnly>(ctx, s, ray, film, sampler, c, visible);
  });
}

}  // namespace kiln
