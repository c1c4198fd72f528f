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
#include "renderer/integrators/vertex_steps.h"

namespace kiln {
namespace {

// Continuations of the Fresnel split beyond the first draw from the sampler's independent tail.
inline constexpr uint32_t kBranchDimension = kStratifiedDimensions;
// Split continuations per camera sample; past it the delta lobe is sampled instead (also unbiased), so glass seen
// through glass cannot multiply the work without bound.
inline constexpr int kMaxSplitBranches = 8;

// A pending continuation of the Fresnel split: a path that left a delta bounce.
struct PathBranch {
  PathState path;
  Rgb potential;
  int depth;
};

// The pending continuations of one camera sample.
struct Branches {
  PathBranch pending[kMaxSplitBranches];
  int n_pending = 0, n_split = 0;
  bool room_for_split() const { return n_split + 2 <= kMaxSplitBranches; }
};

// The course's roulette on arrival at a vertex past the camera's, from the path's potential: Literal flips the coin
// (a survivor's throughput is divided by p; stop: the path ends after this vertex's direct light), Expected flips
// none and weights this vertex's emission and direct light by 1 + extra, extra = 1 - p.
struct ArrivalRoulette {
  bool stop = false;
  float extra = 0.0f;
};

ArrivalRoulette course_roulette(CourseRoulette mode, Rgb potential, uint32_t dim, Sampler& sampler, Rgb& beta) {
  ArrivalRoulette r;
  const float survive = std::min(1.0f, potential.max_component());
  if (mode == CourseRoulette::Expected) {
    r.extra = 1.0f - survive;
  } else if (sampler.set_dimension(dim + kRouletteDimension); sampler.next_float() >= survive) {
    r.stop = true;
  } else {
    beta *= 1.0f / survive;
  }
  return r;
}

// The Fresnel split: every delta branch of m (reflection, refraction) becomes a pending continuation with its
// Fresnel weight, perturbed by the material's roughness.
void split_delta_branches(const Material& m, const SurfaceInteraction& si, const Frame& frame, Vec3f wo, Vec3f wo_l,
                          const PathState& p, Rgb potential, int depth, Sampler& sampler, Branches& b) {
  DeltaBranch branches[2];
  const int nb = m.delta_branches(wo_l, branches);
  sampler.set_dimension(kBranchDimension);
  for (int i = 0; i < nb; ++i) {
    const auto wb_l = perturb(branches[i].wi, m.roughness, sampler.next_2d());
    if (!wb_l) continue;
    const Vec3f wb = frame.to_world(*wb_l);
    const Rgb bb = p.beta * branches[i].weight;
    if (!consistent_sides(si, wo, wb, wo_l, *wb_l) || bb.is_black() || !bb.is_finite()) continue;
    PathState next = p;
    next.beta = bb;
    if (branches[i].transmission) next.eta_scale *= sqr(branches[i].etap);
    next.after_specular = true;
    move_on(next, si, spawn_ray(si.p, si.ng, wb, p.ray.time, si.extent));
    b.pending[b.n_pending++] = PathBranch{next, potential, depth + 1};
    ++b.n_split;
  }
}

template <bool kDelta, bool kDielectric, bool kMeshesOnly>
Rgb course_path(const RenderContext& ctx, const CoursePathSettings& s, const Ray& camera_ray, Vec2f film,
                Sampler& sampler, RayCounters& c, VisibleSurface* visible) {
  const World& w = ctx.world;
  const DirectionSampling directions = s.importance_sampling ? DirectionSampling::Brdf : DirectionSampling::Uniform;
  const bool roulette = s.roulette != CourseRoulette::Off;
  const bool use_nee = s.nee && !w.lights.empty();
  const int max_depth = path_depth_limit(s.max_depth);
  PathState p{camera_ray};
  p.visible = visible;
  Rgb L(0.0f), potential(1.0f);
  Branches branches;
  int start_depth = 0;
  bool first_branch = true;
  Material textured;  // the material of the current vertex when it is textured

  for (;;) {  // the camera path, then any continuations the Fresnel split left pending
    for (int depth = start_depth;; ++depth) {
      const uint32_t dim = first_branch ? vertex_dimension(depth) : kBranchDimension;
      Hit hit;
      const bool found = depth == 0 && s.cull_camera_backfaces ? query_camera_culled(w, p.ray, hit, c)
                                                               : query_intersect(w, p.ray, hit, c, depth == 0);
      if (!found) {
        if (depth == 0) L += p.beta * camera_background(w, film);
        if (p.after_specular || !use_nee)
          L += p.beta * escaped_radiance(w, p.ray.d, LightQuery{}, [](float) { return 1.0f; });
        break;
      }
      SurfaceInteraction si = make_interaction<kMeshesOnly>(w, p.ray, hit);
      const Vec3f wo = -p.ray.d;
      const ArrivalRoulette rr =
          roulette && depth > 0 ? course_roulette(s.roulette, potential, dim, sampler, p.beta) : ArrivalRoulette{};
      if (si.light >= 0 && (p.after_specular || !use_nee))
        L += p.beta * emitted_at(w, si, wo) * (1.0f + rr.extra);
      if (!resolve_material(ctx, si, textured, p, L)) break;
      const bool last_vertex = depth >= max_depth || rr.stop;
      if (last_vertex && !use_nee) break;
      orient_at_vertex<kDielectric>(si, wo, p);
      const Material& m = *si.material;
      const Frame frame(si.ns);
      const Vec3f wo_l = frame.to_local(wo);
      const bool split = kDelta && m.has_delta() && branches.room_for_split();

      if (use_nee && m.has_surface())
        if (const auto dl = sample_direct_light(w, si, frame, wo_l, dim, p.ray.time, sampler, c);
            dl && consistent_sides(si, wo, frame.to_world(dl->wi_local), wo_l, dl->wi_local))
          L += p.beta * dl->value * (1.0f + rr.extra);
      if (last_vertex) break;

      if constexpr (kDelta) {
        if (split) split_delta_branches(m, si, frame, wo, wo_l, p, potential, depth, sampler, branches);
      }
      sampler.set_dimension(dim + kLobeDimension);
      const auto ds = sample_direction<kDelta>(directions, m, wo_l, sampler, split);
      if (!ds) break;
      if constexpr (kDielectric) {
        if (roulette && !ds->specular && is_dielectric(m) && wo_l.z < 0.0f) break;
      }
      // The course refuses directions the shading and geometric normals disagree on (no light through a surface).
      if (!consistent_sides(si, wo, frame.to_world(ds->wi_local), wo_l, ds->wi_local) || !scatter(p, si, frame, *ds))
        break;
      // Delta bounces, which the course follows deterministically, leave the potential alone.
      if (!ds->specular) potential *= ds->f;
      // Expected mode ends paths with Kiln's roulette, from Kiln's depth on.
      const bool kiln_roulette = s.roulette == CourseRoulette::Expected && depth >= kKilnRouletteMinDepth;
      if (kiln_roulette && !survives_roulette(p, dim, sampler)) break;
    }
    if (branches.n_pending == 0) break;
    const PathBranch& b = branches.pending[--branches.n_pending];
    p = b.path;
    potential = b.potential;
    start_depth = b.depth;
    first_branch = false;
  }
  return L;
}

}  // namespace

Rgb integrate(const RenderContext& ctx, const CoursePathSettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
              RayCounters& c, VisibleSurface* visible) {
  return dispatch_on_features(ctx.settings.features, [&]<bool kDelta, bool kDielectric, bool kMeshesOnly>() {
    return course_path<kDelta, kDielectric, kMeshesOnly>(ctx, s, ray, film, sampler, c, visible);
  });
}

}  // namespace kiln
