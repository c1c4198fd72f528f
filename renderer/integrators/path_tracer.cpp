// Kiln's path tracer (pbrt-v4's PathIntegrator::Li in shape): at every vertex, emission found by the sampled ray
// (MIS-weighted against next event estimation), one light sample (MIS-weighted against direction sampling), one
// sampled direction, unbiased throughput roulette after rr_min_depth bounces, at most max_depth bounces.
//
// Strategies: direction sampling by the BSDF, cosine or uniform hemisphere (delta lobes are always sampled); NEE off
// (light is found only by hitting emitters), NEE alone (emitters found by sampled rays are skipped, except from the
// camera and after delta bounces, where NEE could not reach them) or NEE with MIS. All converge to the same image.
#include "renderer/integrators/path_vertex.h"

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
Rgb trace_path_impl(const World& w, const PathSettings& s, const Ray& camera_ray, Vec2f film, Sampler& sampler,
                    RayCounters& c) {
  Rgb L(0.0f), beta(1.0f);
  // Product of eta^2 over transmissions: roulette ignores the 1/eta^2 radiance scaling inside dense glass, which
  // cancels when the path leaves it (pbrt-v4's etaScale).
  float eta_scale = 1.0f;
  Ray ray = camera_ray;
  bool after_specular = true;  // the camera ray counts as one: emitters seen directly are counted in full
  float prev_pdf = 0.0f;
  LightQuery prev{};
  const bool use_nee = s.nee && !w.lights.empty();
  const int max_depth = s.max_depth < 0 ? kMaxPathVertices : std::min(s.max_depth, kMaxPathVertices);
  Material textured;  // the material of the current vertex when it is textured

  for (int depth = 0;; ++depth) {
    Hit hit;
    if (!query_intersect(w, ray, hit, c, depth == 0)) {
      if (depth == 0) L += beta * camera_background(w, film);
      L += beta * escaped_radiance(w, ray.d, prev, [&](float light_pdf) {
             return emission_weight(s, use_nee, after_specular, prev_pdf, light_pdf);
           });
      break;
    }
    SurfaceInteraction si = make_interaction<kMeshesOnly>(w, ray, hit);
    const Vec3f wo = -ray.d;
    if (si.light >= 0) {
      const Rgb le = emitted(w.lights[size_t(si.light)], si.ng, wo);
      if (!le.is_black()) {
        const float light_pdf = after_specular || !s.mis ? 0.0f : emitter_pdf(w, si.light, prev, si);
        L += beta * le * emission_weight(s, use_nee, after_specular, prev_pdf, light_pdf);
      }
    }
    if (!si.material) break;
    if (Rgb unlit; apply_hit_textures(w, si, textured, unlit)) {
      L += beta * unlit;
      break;
    }
    if (depth >= max_depth) break;
    const Material& m = *si.material;
    if constexpr (kDielectric) {
      if (exits_dielectric(si, ray.d)) beta *= m.transmittance(hit.t * length(ray.d));
      orient_normals(si, wo);
    } else if (dot(wo, si.ng) < 0.0f) {
      si.ng = -si.ng;
      si.ns = -si.ns;
    }
    const Frame frame(si.ns);
    const Vec3f wo_l = frame.to_local(wo);
    const uint32_t dim = vertex_dimension(depth);

    if (use_nee && m.has_surface()) {
      if (const auto dl = sample_direct_light(w, si, frame, wo, wo_l, dim, ray.time, sampler, c)) {
        const float weight =
            s.mis && !dl->delta
                ? power_heuristic(dl->light_pdf, direction_pdf<kDelta>(s.directions, m, wo_l, dl->wi_local, false))
                : 1.0f;
        L += beta * dl->value * weight;
      }
    }

    sampler.set_dimension(dim + kLobeDimension);
    const auto ds = sample_direction<kDelta>(s.directions, m, wo_l, sampler, false);
    if (!ds) break;
    const Vec3f wi = frame.to_world(ds->wi_local);
    if (!consistent_sides(si, wo, wi, wo_l, ds->wi_local)) break;
    beta *= ds->f * (abs_cos_theta(ds->wi_local) / ds->pdf);
    if (beta.is_black() || !beta.is_finite()) break;
    if (ds->transmission) eta_scale *= sqr(ds->eta);
    after_specular = ds->specular;
    prev_pdf = ds->pdf;
    prev = LightQuery{si.p, si.ns};

    if (s.russian_roulette && depth >= s.rr_min_depth) {
      const float survive = std::min(1.0f, beta.max_component() * eta_scale);
      sampler.set_dimension(dim + kRouletteDimension);
      if (sampler.next_float() >= survive) break;
      beta *= 1.0f / survive;
    }
    ray = spawn_ray(si.p, si.ng, wi, ray.time, si.extent);
  }
  return L;
}

}  // namespace

Rgb trace_path(const World& w, const PathSettings& s, uint32_t features, const Ray& ray, Vec2f film,
               Sampler& sampler, RayCounters& c) {
  return dispatch_on_features(features, [&](auto delta, auto dielectric, auto meshes_only) {
    return trace_path_impl<decltype(delta)::value, decltype(dielectric)::value, decltype(meshes_only)::value>(
        w, s, ray, film, sampler, c);
  });
}

}  // namespace kiln
