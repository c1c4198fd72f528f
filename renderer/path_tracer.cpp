// Unidirectional path tracer: uniform / cosine / BRDF direction sampling, next event estimation through the
// light selector, Russian roulette, and MIS (power heuristic) between NEE and direction sampling.
//
// Emission found by a sampled direction is counted in full for camera rays, after delta bounces and when NEE is
// off; with NEE and no MIS it is skipped (NEE already counted it); with MIS it is weighted.
#include "renderer/integrator.h"
#include "renderer/ray_query.h"
#include "renderer/shading.h"

namespace kiln {
namespace {

// Sampler requests of one path vertex, in this order: course roulette, NEE light choice, NEE position, lobe
// choice, direction, Kiln's roulette. Each vertex starts at its own fixed dimension whatever was skipped before.
inline constexpr uint32_t kCourseRouletteDimension = 0;
inline constexpr uint32_t kNeeDimension = 1;        // light choice, then a 2D position
inline constexpr uint32_t kDirectionDimension = 3;  // lobe choice, then a 2D direction
inline constexpr uint32_t kRouletteDimension = 5;
inline constexpr uint32_t kDimensionsPerVertex = 6;
// Continuations of the course's Fresnel split beyond the first draw from the sampler's independent tail.
inline constexpr uint32_t kBranchDimension = kStratifiedDimensions;
// Split continuations per camera sample; past it the delta lobe is sampled instead (also unbiased), so glass seen
// through glass cannot multiply the work without bound.
inline constexpr int kMaxSplitBranches = 8;

// A pending continuation of the course's Fresnel split.
struct PathBranch {
  Ray ray;
  Rgb beta, potential;
  float eta_scale;
  int depth;
};

struct DirectionSample {
  Vec3f wi_local;
  Rgb f;
  float pdf = 0;
  bool specular = false;
  bool transmission = false;
  float eta = 1.0f;  // relative IOR crossed (transmission)
};

// Probability of choosing the delta part; compiled out for scenes without delta materials.
template <bool kDelta>
float delta_prob(const Material& m, Vec3f wo_l) {
  if constexpr (kDelta) return m.delta_probability(wo_l);
  else return 0.0f;
}

// Solid-angle pdf with which the active strategy would have produced wi_l (for MIS weights).
template <bool kDelta>
float strategy_pdf(const IntegratorSettings& s, const Material& m, Vec3f wo_l, Vec3f wi_l, bool surface_only) {
  const float keep = surface_only ? 1.0f : 1.0f - delta_prob<kDelta>(m, wo_l);
  switch (s.directions) {
    case DirectionSampling::Brdf:
      return surface_only ? m.pdf_surface(wo_l, wi_l) : m.pdf(wo_l, wi_l);
    case DirectionSampling::Cosine:
      return keep * cosine_hemisphere_pdf(wi_l.z);
    case DirectionSampling::Uniform:
      return wi_l.z > 0.0f ? keep * uniform_hemisphere_pdf() : 0.0f;
  }
  return 0.0f;
}

template <bool kDelta>
std::optional<DirectionSample> sample_direction(const IntegratorSettings& s, const Material& m, Vec3f wo_l, Sampler& sampler,
                                                bool surface_only) {
  const float uc = sampler.next_float();
  const Vec2f u = sampler.next_2d();
  if (surface_only && !m.has_surface()) return std::nullopt;
  if (s.directions == DirectionSampling::Brdf) {
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
  // Surface lobe through a BRDF-independent warp; the hemisphere is the one wo lies in (opaque surfaces are
  // already oriented so that wo.z > 0).
  Vec3f wi = s.directions == DirectionSampling::Cosine ? sample_cosine_hemisphere(u) : sample_uniform_hemisphere(u);
  float pdf = s.directions == DirectionSampling::Cosine ? cosine_hemisphere_pdf(wi.z) : uniform_hemisphere_pdf();
  if (wo_l.z < 0.0f) wi.z = -wi.z;
  pdf *= (1.0f - pd);
  if (pdf <= 0.0f) return std::nullopt;
  return DirectionSample{wi, m.eval(wo_l, wi), pdf, false, false};
}

// The path loop, specialised on the scene's feature mask (Cycles-style): a scene without delta materials
// never asks for delta probabilities, one without dielectrics never tracks media, one with only world-space meshes
// (no spheres, no instances) skips the shape dispatch.
template <bool kDelta, bool kDielectric, bool kMeshesOnly>
Rgb trace_path_impl(const World& w, const IntegratorSettings& s, const Ray& camera_ray, Sampler& sampler, RayCounters& c) {
  Rgb L(0.0f), beta(1.0f), potential(1.0f);
  // Product of eta^2 over transmissions: undoes the 1/eta^2 radiance scaling for the roulette decision, so paths
  // inside dense glass are not killed for a scale factor that cancels when they leave (pbrt-v4's etaScale).
  float eta_scale = 1.0f;
  Ray ray = camera_ray;
  bool specular_bounce = true;  // the camera ray counts as one: emitters seen directly are always counted
  float prev_pdf = 0.0f;
  LightQuery prev{};
  const bool use_nee = s.nee && !w.lights.empty();
  const int max_depth = s.max_depth < 0 ? kMaxPathVertices : std::min(s.max_depth, kMaxPathVertices);
  PathBranch pending[kMaxSplitBranches];
  int n_pending = 0, n_split = 0, start_depth = 0;
  bool first_branch = true;

  for (;;) {  // the camera path, then any continuations the Fresnel split left pending
    for (int depth = start_depth;; ++depth) {
      const uint32_t dim =
          first_branch ? kFirstPathDimension + uint32_t(depth) * kDimensionsPerVertex : kBranchDimension;
      Hit hit;
      if (!query_intersect(w, ray, hit, c, depth == 0)) {
        if (depth == 0) L += beta * w.background;
        break;
      }
      SurfaceInteraction si = make_interaction<kMeshesOnly>(w, ray, hit);
      const Vec3f wo = -ray.d;
      // Course roulette (spec §11, README "Course path-tracing semantics"): decided on arrival at a vertex from the
      // path's "potential", the product of the BRDF VALUES f (not the reflectances f*pi) of its diffuse / glossy
      // bounces; a surviving path divides everything it gathers from here on, including this vertex's own emission
      // and NEE, by the survival probability p, while a terminated path still keeps this vertex's direct light. In
      // expectation that weights this vertex's direct light by p * (1/p) + (1 - p) = 2 - p and leaves later vertices
      // alone: about x1.74 from the first bounce on (x1.94 from the second), which is what makes the course's
      // RussianRoulette references 25-50% brighter than its depth-capped ones. Expected mode applies exactly that
      // weight and lets Kiln's unbiased roulette end the path; Literal replays the course's coin flips (survivors
      // weigh kd^k (pi/kd)^(k(k+1)/2) with cosine-sampled diffuse bounces: the references' ~590 fireflies).
      bool course_stop = false;
      float course_extra = 0.0f;  // Expected mode: the terminated branch's share 1 - p of this vertex's direct light
      if (s.course_roulette != CourseRoulette::Off && depth > 0) {
        const float survive = std::min(1.0f, potential.max_component());
        if (s.course_roulette == CourseRoulette::Expected) {
          course_extra = 1.0f - survive;
        } else if (sampler.set_dimension(dim + kCourseRouletteDimension); sampler.next_float() >= survive) {
          course_stop = true;
        } else {
          beta *= 1.0f / survive;
        }
      }
      if (si.light >= 0) {
        const Light& light = w.lights[size_t(si.light)];
        const Rgb le = emitted(light, si.ng, wo);
        if (!le.is_black()) {
          if (specular_bounce || !use_nee) {
            L += beta * le * (1.0f + course_extra);
          } else if (s.mis) {
            const float light_pdf = pdf_li(light, prev, si.p, si.ng, si.prim) * w.light_selector.pmf(size_t(si.light));
            L += beta * le * (power_heuristic(prev_pdf, light_pdf) * (1.0f + course_extra));
          }
        }
      }
      if (!si.material) break;
      // Kiln: max_depth bounces, so the last vertex only collects emission. The course's recursion also runs
      // NEE there (one more bounce of light for NEE paths than for pure path tracing; README).
      const bool last_vertex = depth >= max_depth || course_stop;
      if (last_vertex && !(s.nee_at_last_vertex && use_nee)) break;
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
      // Course rule (spec §11): mirror / dielectric parts are followed deterministically, every Fresnel branch with
      // its weight, next to the one sampled surface direction (which then no longer competes with the delta part).
      const bool split = kDelta && s.split_delta && m.has_delta() && n_split + 2 <= kMaxSplitBranches;

      if (use_nee && m.has_surface()) {
        float pmf = 0.0f;
        sampler.set_dimension(dim + kNeeDimension);
        const size_t li = w.light_selector.sample(sampler.next_float(), &pmf);
        const Vec2f u = sampler.next_2d();
        if (pmf > 0.0f) {
          const auto ls = sample_li(w.lights[li], LightQuery{si.p, si.ns}, u);
          if (ls && ls->pdf > 0.0f && !ls->li.is_black() && valid_reflection_side(si, wo, ls->wi)) {
            const Vec3f wi_l = frame.to_local(ls->wi);
            const Rgb f = m.eval(wo_l, wi_l);
            if (!f.is_black() && !query_occluded(w, spawn_ray_to(si.p, si.ng, ls->p_light), c)) {
              const float light_pdf = ls->pdf * pmf;
              // At the course's last vertex no direction is sampled after NEE, so NEE carries the full weight.
              const bool combine = s.mis && !ls->delta && !last_vertex;
              // Course roulette, Expected mode: the terminated branch (share 1 - p) gathers NEE as a last vertex.
              const float weight = (combine ? power_heuristic(light_pdf, strategy_pdf<kDelta>(s, m, wo_l, wi_l, split)) : 1.0f) +
                                   (s.nee_at_last_vertex ? course_extra : 0.0f);
              L += beta * f * ls->li * (abs_cos_theta(wi_l) * weight / light_pdf);
            }
          }
        }
      }

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
            if ((!branches[i].transmission && !valid_reflection_side(si, wo, wb)) || bb.is_black() || !bb.is_finite())
              continue;
            const float es = branches[i].transmission ? eta_scale * sqr(branches[i].etap) : eta_scale;
            pending[n_pending++] = PathBranch{spawn_ray(si.p, si.ng, wb), bb, potential, es, depth + 1};
            ++n_split;
          }
        }
      }
      sampler.set_dimension(dim + kDirectionDimension);
      const auto ds = sample_direction<kDelta>(s, m, wo_l, sampler, split);
      if (!ds) break;
      // The course's glossy coat of a dielectric scatters only outside. Kiln's coat is two-sided: from inside it
      // can turn a ray beyond the critical angle, total internal reflection in a sphere then keeps it there for
      // good, and the course roulette (survival 1 while the potential is >= 1) would never end it.
      if constexpr (kDielectric) {
        if (s.course_roulette != CourseRoulette::Off && !ds->specular && is_dielectric(m) && wo_l.z < 0.0f) break;
      }
      const Vec3f wi = frame.to_world(ds->wi_local);
      if (!ds->transmission && !valid_reflection_side(si, wo, wi)) break;
      beta *= ds->f * (abs_cos_theta(ds->wi_local) / ds->pdf);
      // The course potential: BRDF values of the diffuse / glossy bounces; delta bounces, which the course follows
      // deterministically, leave it alone (their sample weights carry Kiln's lobe-selection factors).
      if (!ds->specular) potential *= ds->f;
      if (beta.is_black() || !beta.is_finite()) break;
      if (ds->transmission) eta_scale *= sqr(ds->eta);
      specular_bounce = ds->specular;
      prev_pdf = ds->pdf;
      prev = LightQuery{si.p, si.ns};

      if (s.russian_roulette && s.course_roulette != CourseRoulette::Literal && depth >= s.rr_min_depth) {
        // Survival probability from the throughput; dividing by it keeps the estimator unbiased.
        const float survive = std::min(1.0f, beta.max_component() * eta_scale);
        sampler.set_dimension(dim + kRouletteDimension);
        if (sampler.next_float() >= survive) break;
        beta *= 1.0f / survive;
      }
      ray = spawn_ray(si.p, si.ng, wi);
    }
    if (n_pending == 0) break;
    const PathBranch& b = pending[--n_pending];
    ray = b.ray;
    beta = b.beta;
    potential = b.potential;
    eta_scale = b.eta_scale;
    start_depth = b.depth;
    specular_bounce = true;  // a delta bounce: emitters it reaches are counted in full
    prev_pdf = 0.0f;
    first_branch = false;
  }
  if (s.clamp > 0.0f) {
    const float mx = L.max_component();
    if (mx > s.clamp) L *= s.clamp / mx;
  }
  return L;
}

}  // namespace

Rgb trace_path(const World& w, const IntegratorSettings& s, const Ray& ray, Sampler& sampler, RayCounters& c) {
  const bool delta = s.features & kFeatureDelta, dielectric = s.features & kFeatureDielectric;
  if (!(s.features & (kFeatureSpheres | kFeatureInstances))) {
    if (dielectric) return trace_path_impl<true, true, true>(w, s, ray, sampler, c);
    if (delta) return trace_path_impl<true, false, true>(w, s, ray, sampler, c);
    return trace_path_impl<false, false, true>(w, s, ray, sampler, c);
  }
  if (dielectric) return trace_path_impl<true, true, false>(w, s, ray, sampler, c);
  if (delta) return trace_path_impl<true, false, false>(w, s, ray, sampler, c);
  return trace_path_impl<false, false, false>(w, s, ray, sampler, c);
}

}  // namespace kiln
