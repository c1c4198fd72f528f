// The CENG795 course's path tracer (spec §11, README "Course conventions"), reproducing its reference renders. Built
// from the same pieces as Kiln's path tracer (renderer/integrators/path_vertex.h) with the course's rules on top:
// - directions are uniform over the hemisphere, or BRDF-sampled with ImportanceSampling; no MIS;
// - with NextEventEstimation, one light per vertex, also at the vertex at MaxRecursionDepth (NEE paths carry one
//   bounce of light more than pure path tracing); emitters hit by sampled rays then count only from the camera and
//   after delta bounces;
// - mirror and dielectric parts are followed deterministically, every Fresnel branch with its weight, beside the one
//   sampled surface direction (the Fresnel split);
// - RussianRoulette replaces the depth cap (renderer/integrators/rules.cpp). It is decided on arrival at a vertex from the path's "potential", the
//   product of the BRDF values f (not the reflectances) of its diffuse / glossy bounces; a surviving path divides
//   what it gathers from there on, including this vertex's own emission and NEE, by the survival probability p, a
//   terminated one still keeps this vertex's direct light. In expectation that weights the direct light of the vertex
//   by p * (1/p) + (1 - p) = 2 - p: the course's RussianRoulette references are 25-50% brighter than its depth-capped
//   ones. Literal replays the coin flips (survivors weigh kd^k (pi/kd)^(k(k+1)/2)); Expected applies the 2 - p weight
//   and ends paths with Kiln's unbiased throughput roulette;
// - the glossy coat of a dielectric scatters only outside (from inside, total internal reflection in a sphere would
//   keep a coat-scattered path there for good, and the course roulette, surviving while the potential is >= 1,
//   would never end it).
#include "renderer/integrators/path_vertex.h"

namespace kiln {
namespace {

// Continuations of the Fresnel split beyond the first draw from the sampler's independent tail.
inline constexpr uint32_t kBranchDimension = kStratifiedDimensions;
// Split continuations per camera sample; past it the delta lobe is sampled instead (also unbiased), so glass seen
// through glass cannot multiply the work without bound.
inline constexpr int kMaxSplitBranches = 8;
// Expected mode ends paths with Kiln's roulette after this many bounces.
inline constexpr int kExpectedModeRrMinDepth = 3;

// A pending continuation of the Fresnel split.
struct PathBranch {
  Ray ray;
  Rgb beta, potential;
  float eta_scale;
  int depth;
};

template <bool kDelta, bool kDielectric, bool kMeshesOnly>
Rgb trace_course_path_impl(const World& w, const CoursePathSettings& s, const Ray& camera_ray, Vec2f film,
                           Sampler& sampler, RayCounters& c) {
  const DirectionSampling directions = s.importance_sampling ? DirectionSampling::Brdf : DirectionSampling::Uniform;
  const bool roulette = s.roulette != CourseRoulette::Off;
  const bool use_nee = s.nee && !w.lights.empty();
  const int max_depth = s.max_depth < 0 ? kMaxPathVertices : std::min(s.max_depth, kMaxPathVertices);
  Rgb L(0.0f), beta(1.0f), potential(1.0f);
  float eta_scale = 1.0f;
  Ray ray = camera_ray;
  bool after_specular = true;
  PathBranch pending[kMaxSplitBranches];
  int n_pending = 0, n_split = 0, start_depth = 0;
  bool first_branch = true;
  Material textured;  // the material of the current vertex when it is textured

  for (;;) {  // the camera path, then any continuations the Fresnel split left pending
    for (int depth = start_depth;; ++depth) {
      const uint32_t dim = first_branch ? vertex_dimension(depth) : kBranchDimension;
      Hit hit;
      const bool found = depth == 0 && s.cull_camera_backfaces ? query_camera_culled(w, ray, hit, c)
                                                               : query_intersect(w, ray, hit, c, depth == 0);
      if (!found) {
        if (depth == 0) L += beta * camera_background(w, film);
        if (after_specular || !use_nee) L += beta * escaped_radiance(w, ray.d, LightQuery{}, [](float) { return 1.0f; });
        break;
      }
      SurfaceInteraction si = make_interaction<kMeshesOnly>(w, ray, hit);
      const Vec3f wo = -ray.d;
      bool stop = false;
      float extra = 0.0f;  // Expected mode: the terminated branch's share 1 - p of this vertex's direct light
      if (roulette && depth > 0) {
        const float survive = std::min(1.0f, potential.max_component());
        if (s.roulette == CourseRoulette::Expected) {
          extra = 1.0f - survive;
        } else if (sampler.set_dimension(dim + kRouletteDimension); sampler.next_float() >= survive) {
          stop = true;
        } else {
          beta *= 1.0f / survive;
        }
      }
      if (si.light >= 0 && (after_specular || !use_nee))
        L += beta * emitted(w.lights[size_t(si.light)], si.ng, wo) * (1.0f + extra);
      if (!si.material) break;
      if (Rgb unlit; apply_hit_textures(w, si, textured, unlit)) {
        L += beta * unlit;
        break;
      }
      const bool last_vertex = depth >= max_depth || stop;
      if (last_vertex && !use_nee) break;
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
      const bool split = kDelta && m.has_delta() && n_split + 2 <= kMaxSplitBranches;

      if (use_nee && m.has_surface())
        if (const auto dl = sample_direct_light(w, si, frame, wo, wo_l, dim, ray.time, sampler, c))
          L += beta * dl->value * (1.0f + extra);
      if (last_vertex) break;

      if constexpr (kDelta) {
        if (split) {
          DeltaBranch branches[2];
          const int nb = m.delta_branches(wo_l, branches);
          sampler.set_dimension(kBranchDimension);
          for (int i = 0; i < nb; ++i) {
            const auto wb_l = perturb(branches[i].wi, m.roughness, sampler.next_2d());
            if (!wb_l) continue;
            const Vec3f wb = frame.to_world(*wb_l);
            const Rgb bb = beta * branches[i].weight;
            if (!consistent_sides(si, wo, wb, wo_l, *wb_l) || bb.is_black() || !bb.is_finite()) continue;
            const float es = branches[i].transmission ? eta_scale * sqr(branches[i].etap) : eta_scale;
            pending[n_pending++] = PathBranch{spawn_ray(si.p, si.ng, wb, ray.time, si.extent), bb, potential, es, depth + 1};
            ++n_split;
          }
        }
      }
      sampler.set_dimension(dim + kLobeDimension);
      const auto ds = sample_direction<kDelta>(directions, m, wo_l, sampler, split);
      if (!ds) break;
      if constexpr (kDielectric) {
        if (roulette && !ds->specular && is_dielectric(m) && wo_l.z < 0.0f) break;
      }
      const Vec3f wi = frame.to_world(ds->wi_local);
      if (!consistent_sides(si, wo, wi, wo_l, ds->wi_local)) break;
      beta *= ds->f * (abs_cos_theta(ds->wi_local) / ds->pdf);
      // Delta bounces, which the course follows deterministically, leave the potential alone.
      if (!ds->specular) potential *= ds->f;
      if (beta.is_black() || !beta.is_finite()) break;
      if (ds->transmission) eta_scale *= sqr(ds->eta);
      after_specular = ds->specular;

      if (s.roulette == CourseRoulette::Expected && depth >= kExpectedModeRrMinDepth) {
        const float survive = std::min(1.0f, beta.max_component() * eta_scale);
        sampler.set_dimension(dim + kRouletteDimension);
        if (sampler.next_float() >= survive) break;
        beta *= 1.0f / survive;
      }
      ray = spawn_ray(si.p, si.ng, wi, ray.time, si.extent);
    }
    if (n_pending == 0) break;
    const PathBranch& b = pending[--n_pending];
    ray = b.ray;
    beta = b.beta;
    potential = b.potential;
    eta_scale = b.eta_scale;
    start_depth = b.depth;
    after_specular = true;  // a delta bounce: emitters it reaches are counted in full
    first_branch = false;
  }
  return L;
}

}  // namespace

Rgb trace_course_path(const World& w, const CoursePathSettings& s, uint32_t features, const Ray& ray, Vec2f film,
                      Sampler& sampler, RayCounters& c) {
  return dispatch_on_features(features, [&](auto delta, auto dielectric, auto meshes_only) {
    return trace_course_path_impl<decltype(delta)::value, decltype(dielectric)::value, decltype(meshes_only)::value>(
        w, s, ray, film, sampler, c);
  });
}

}  // namespace kiln
