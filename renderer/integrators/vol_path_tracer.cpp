// Kiln's volumetric path tracer: Kiln's path tracer (path_tracer.cpp) through participating media, in the shape of
// pbrt-v4's VolPathIntegrator::Li. Along every ray segment inside a medium, delta tracking samples tentative
// collisions against the medium's majorants (media/tracking.h): each is an absorption (the path ends), a real
// scattering (a path vertex: light sample, phase-function direction) or a null collision (the walk goes on).
// Light samples reach their light through media by ratio tracking. Surfaces with pbrt's "interface" material only
// mark where the medium changes: the ray crosses them without a bounce.
//
// Chromatic media (extinction differing across RGB): distances are sampled on one channel per path, the hero,
// chosen uniformly from the sampler. Besides the throughput beta the path carries r_u and r_l (pbrt-v4's rescaled
// path probabilities): per channel c, the density with which tracking on c would have produced the path by
// direction sampling (r_u) or by light sampling (r_l), divided by the density of the path actually sampled. Every
// contribution is divided by the average of the densities it could have come from, which is the balance heuristic
// over both the channels and the two strategies (NEE and direction sampling). With PathSettings::channel_mis false
// only the hero channel's densities count (unbiased as well, and noisier where the channels differ).
//
// Depth counts as pbrt counts it: real scattering events, in media and at surfaces; medium boundaries do not count.
// Roulette follows Kiln's path tracer (after rr_min_depth scattering events, on beta / r_u), also after medium
// scattering. Strategies are Kiln's: uniform or cosine directions at surfaces (uniform directions over the sphere
// at medium vertices, phase sampling otherwise), NEE on or off, MIS on or off.
#include <cstring>

#include "renderer/integrators/vertex_steps.h"

namespace kiln {
namespace {

// Sampler layout: the path's hero channel and the seed of its tracking random numbers first, then one block per
// ray segment: a vertex's requests (path_vertex.h) and the segment's first tentative collision.
inline constexpr uint32_t kHeroChannelDimension = kFirstPathDimension;          // 1D
inline constexpr uint32_t kTrackingSeedDimension = kFirstPathDimension + 1;     // 2D
inline constexpr uint32_t kFirstSegmentDimension = kFirstPathDimension + 2;
inline constexpr uint32_t kCollisionDimension = kDimensionsPerVertex;            // 1D, within a segment's block
inline constexpr uint32_t kDimensionsPerSegment = kDimensionsPerVertex + 1;

uint32_t segment_dimension(int segment) { return kFirstSegmentDimension + uint32_t(segment) * kDimensionsPerSegment; }

// Ray segments one path may trace (vertices and medium boundaries crossed): a ray caught between coincident
// boundaries must still end.
inline constexpr int kMaxSegments = 4 * kMaxPathVertices;

// Ratio tracking plays roulette with a shadow ray whose transmittance estimate falls below kShadowRouletteBelow,
// ending it with probability kShadowRouletteEnd (pbrt-v4's 0.05 and 0.75).
inline constexpr float kShadowRouletteBelow = 0.05f;
inline constexpr float kShadowRouletteEnd = 0.75f;

// beta, r_u and r_l enter every estimate as ratios, so they are rescaled together once r_u grows past this: in a
// strongly chromatic medium the other channels' densities relative to the hero's multiply up along the path and
// would otherwise overflow.
inline constexpr float kRescaleAbove = 1e16f;

Rgb clamp_zero(Rgb c) { return {std::max(0.0f, c.r), std::max(0.0f, c.g), std::max(0.0f, c.b)}; }

uint64_t bits_of(float x) {
  uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// The way from a scattering vertex to a light sample: the vertex's f * |cos| (or phase function), the density with
// which the vertex's direction sampling would pick that direction, and the shadow ray with its starting medium.
struct LightConnection {
  Rgb f;
  float scatter_pdf = 0.0f;
  Ray shadow;
  int medium = -1;
};

template <bool kDelta, bool kDielectric, bool kMeshesOnly>
class VolumetricPath {
 public:
  VolumetricPath(const RenderContext& ctx, const PathSettings& s, Sampler& sampler, RayCounters& c)
      : ctx_(ctx),
        w_(ctx.world),
        s_(s),
        sampler_(sampler),
        c_(c),
        use_nee_(s.nee && !ctx.world.lights.empty()),
        max_depth_(path_depth_limit(s.max_depth)) {
    sampler_.set_dimension(kHeroChannelDimension);
    hero_ = std::min(2, int(sampler_.next_float() * 3.0f));
    sampler_.set_dimension(kTrackingSeedDimension);
    const Vec2f seed = sampler_.next_2d();
    rng_ = Rng(mix64(bits_of(seed.x)), mix64(bits_of(seed.y) + 1));
  }

  Rgb trace(const Ray& camera_ray, int camera_medium, Vec2f film, VisibleSurface* visible) {
    p_.ray = camera_ray;
    p_.visible = visible;
    medium_ = camera_medium;
    Material textured;  // the material of the current vertex when it is textured
    for (int segment = 0; segment < kMaxSegments; ++segment) {
      const uint32_t dim = segment_dimension(segment);
      Hit hit;
      const bool found = query_intersect(w_, p_.ray, hit, c_, segment == 0);
      if (medium_ >= 0) {
        const Step step = track_medium(found ? hit.t : kInfinity, dim);
        if (step == Step::Ended) break;
        if (step == Step::Scattered) continue;
      }
      if (!found) {
        add_escaped(film);
        break;
      }
      SurfaceInteraction si = make_interaction<kMeshesOnly>(w_, p_.ray, hit);
      add_surface_emission(si);
      if (si.material && si.material->passes_through) {
        cross_boundary(si);
        continue;
      }
      if (!si.material) {
        see_resolved_surface(p_.visible, si, p_.ray, p_.travelled, nullptr);
        break;
      }
      if (Rgb unlit; apply_hit_textures(ctx_, si, textured, unlit)) {
        L_ += p_.beta * unlit / average(r_u_);
        see_resolved_surface(p_.visible, si, p_.ray, p_.travelled, &unlit);
        break;
      }
      see_resolved_surface(p_.visible, si, p_.ray, p_.travelled, nullptr);
      if (depth_++ >= max_depth_) break;
      if (!scatter_at_surface(si, dim) || !roulette(dim)) break;
    }
    return L_;
  }

 private:
  enum class Step { Passed, Scattered, Ended };

  // The balance heuristic's denominator: the densities averaged over the channels, or the hero's alone.
  float average(Rgb r) const { return s_.channel_mis ? r.average() : r[hero_]; }

  void rescale() {
    const float m = r_u_.max_component();
    if (!(m > kRescaleAbove)) return;
    const float k = 1.0f / m;
    p_.beta *= k;
    r_u_ *= k;
    r_l_ *= k;
  }

  void count_collision(const MediumProperties& mp, Rgb sigma_maj) {
    ++c_.media.collisions;
    c_.media.extinction_ratio += double((mp.sigma_a[hero_] + mp.sigma_s[hero_]) / sigma_maj[hero_]);
  }

  // ---- through a medium ----

  // Delta tracking along the current ray up to tmax (its surface, or infinity): the path ends (absorption, depth,
  // nothing left to carry), scatters (a new ray) or passes to tmax.
  Step track_medium(float tmax, uint32_t dim) {
    ++c_.media.rays;
    sampler_.set_dimension(dim + kCollisionDimension);
    const float u = sampler_.next_float();
    bool scattered = false, ended = false;
    Vec3f scatter_point;
    const Rgb t_end = sample_collisions(
        w_.media[size_t(medium_)], p_.ray, tmax, u, rng_, hero_,
        [&](Vec3f p, const MediumProperties& mp, Rgb sigma_maj, Rgb t_maj) {
          count_collision(mp, sigma_maj);
          if (depth_ < max_depth_ && !mp.le.is_black()) add_medium_emission(mp, sigma_maj, t_maj);
          const float p_absorb = mp.sigma_a[hero_] / sigma_maj[hero_];
          const float p_scatter = mp.sigma_s[hero_] / sigma_maj[hero_];
          const float um = rng_.next_float();
          if (um < p_absorb) {
            ended = true;
            return false;
          }
          if (um < p_absorb + p_scatter) {
            ended = depth_++ >= max_depth_;
            if (!ended) real_scattering(mp, t_maj);
            scattered = !ended;
            scatter_point = p;
            return false;
          }
          null_collision(mp, sigma_maj, t_maj);
          return !p_.beta.is_black() && !r_u_.is_black();
        });
    if (ended || p_.beta.is_black() || r_u_.is_black()) return Step::Ended;
    if (scattered) return scatter_in_medium(scatter_point, dim) && roulette(dim) ? Step::Scattered : Step::Ended;
    if (!(t_end[hero_] > 0.0f)) return Step::Ended;
    const Rgb ratio = t_end / t_end[hero_];
    p_.beta *= ratio;
    r_u_ *= ratio;
    r_l_ *= ratio;
    return Step::Passed;
  }

  // Emission of the medium at a tentative collision: sigma_a Le over the majorant's collision density.
  void add_medium_emission(const MediumProperties& mp, Rgb sigma_maj, Rgb t_maj) {
    const float pdf = sigma_maj[hero_] * t_maj[hero_];
    const Rgb r_e = r_u_ * sigma_maj * t_maj / pdf;
    const float denominator = average(r_e);
    if (denominator > 0.0f) L_ += p_.beta * t_maj / pdf * mp.sigma_a * mp.le / denominator;
  }

  void real_scattering(const MediumProperties& mp, Rgb t_maj) {
    const float pdf = t_maj[hero_] * mp.sigma_s[hero_];
    p_.beta *= t_maj * mp.sigma_s / pdf;
    r_u_ *= t_maj * mp.sigma_s / pdf;
    rescale();
  }

  void null_collision(const MediumProperties& mp, Rgb sigma_maj, Rgb t_maj) {
    const Rgb sigma_n = clamp_zero(sigma_maj - mp.sigma_a - mp.sigma_s);
    const float pdf = t_maj[hero_] * sigma_n[hero_];
    if (!(pdf > 0.0f)) {
      p_.beta = Rgb(0.0f);
      return;
    }
    p_.beta *= t_maj * sigma_n / pdf;
    r_u_ *= t_maj * sigma_n / pdf;
    r_l_ *= t_maj * sigma_maj / pdf;
    rescale();
  }

  // The vertex of a real scattering event at p: a light sample, then a direction from the phase function.
  bool scatter_in_medium(Vec3f p, uint32_t dim) {
    const HenyeyGreenstein& phase = medium_phase(w_.media[size_t(medium_)]);
    const Vec3f wo = -p_.ray.d;
    const bool uniform = s_.directions == DirectionSampling::Uniform;
    const auto phase_pdf = [&](Vec3f wi) { return uniform ? uniform_sphere_pdf() : phase.pdf(wo, wi); };
    const LightQuery here{p, Vec3f(0.0f)};
    if (use_nee_)
      add_direct_light(here, dim, [&](const LightSample& ls) -> std::optional<LightConnection> {
        return LightConnection{Rgb(phase.p(wo, ls.wi)), phase_pdf(ls.wi),
                               Ray{p, ls.p_light - p, 0.0f, kShadowRayEndFraction, p_.ray.time}, medium_};
      });
    sampler_.set_dimension(dim + kDirectionDimension);
    const Vec2f u = sampler_.next_2d();
    Vec3f wi;
    float f, pdf;
    if (uniform) {
      wi = sample_uniform_sphere(u);
      f = phase.p(wo, wi);
      pdf = uniform_sphere_pdf();
    } else {
      const auto ps = phase.sample(wo, u);
      if (!ps) return false;
      wi = ps->wi;
      f = ps->p;
      pdf = ps->pdf;
    }
    p_.beta *= f / pdf;
    r_l_ = r_u_ / pdf;
    p_.after_specular = false;
    prev_ = here;
    if (p_.visible && !p_.visible->found) p_.travelled += length(p - p_.ray.o);
    p_.ray = Ray{p, wi, 0.0f, kInfinity, p_.ray.time};
    return !p_.beta.is_black();
  }

  // ---- at surfaces ----

  void add_surface_emission(const SurfaceInteraction& si) {
    if (si.light < 0) return;
    const Rgb le = emitted_at(w_, si, -p_.ray.d);
    if (le.is_black()) return;
    if (p_.after_specular || !use_nee_) {
      L_ += p_.beta * le / average(r_u_);
    } else if (s_.mis) {
      const float light_pdf = emitter_pdf(w_, si.light, prev_, si);
      L_ += p_.beta * le / average(r_u_ + r_l_ * light_pdf);
    }
  }

  void add_escaped(Vec2f film) {
    if (depth_ == 0) L_ += p_.beta * camera_background(w_, film) / average(r_u_);
    L_ += p_.beta * escaped_radiance(w_, p_.ray.d, prev_, [&](float light_pdf) {
            if (p_.after_specular || !use_nee_) return 1.0f / average(r_u_);
            return s_.mis ? 1.0f / average(r_u_ + r_l_ * light_pdf) : 0.0f;
          });
  }

  // A surface that only bounds media: the ray goes on in the medium on the far side.
  void cross_boundary(const SurfaceInteraction& si) {
    const MediumInterface& sides = w_.shape_data[si.shape].media;
    if (sides.transition()) medium_ = sides.entered(p_.ray.d, si.ng);
    move_on(p_, si, spawn_ray(si.p, si.ng, p_.ray.d, p_.ray.time, si.extent));
  }

  bool scatter_at_surface(SurfaceInteraction& si, uint32_t dim) {
    const Material& m = *si.material;
    const Vec3f wo = -p_.ray.d;
    const Vec3f outward = si.ng;  // the shape's own orientation, which tells its media apart
    orient_at_vertex<kDielectric>(si, wo, p_);
    const Frame frame(si.ns);
    const Vec3f wo_l = frame.to_local(wo);
    const MediumInterface& sides = w_.shape_data[si.shape].media;
    const auto medium_towards = [&](Vec3f w) { return sides.transition() ? sides.entered(w, outward) : medium_; };

    if (use_nee_ && m.has_surface())
      add_direct_light(LightQuery{si.p, si.ns}, dim, [&](const LightSample& ls) -> std::optional<LightConnection> {
        const Vec3f wi_l = frame.to_local(ls.wi);
        return LightConnection{m.eval(wo_l, wi_l) * abs_cos_theta(wi_l),
                               direction_pdf<kDelta>(s_.directions, m, wo_l, wi_l, false),
                               spawn_ray_to(si.p, si.ng, ls.p_light, p_.ray.time, si.extent), medium_towards(ls.wi)};
      });

    sampler_.set_dimension(dim + kLobeDimension);
    const auto ds = sample_direction<kDelta>(s_.directions, m, wo_l, sampler_, false);
    if (!ds || !scatter(p_, si, frame, *ds)) return false;
    r_l_ = r_u_ / ds->pdf;
    prev_ = LightQuery{si.p, si.ns};
    medium_ = medium_towards(p_.ray.d);
    return true;
  }

  // Kiln's throughput roulette on the path's estimate beta / r_u, after rr_min_depth scattering events.
  bool roulette(uint32_t dim) {
    if (!s_.russian_roulette || depth_ <= s_.rr_min_depth) return true;
    const float survive = roulette_survival((p_.beta * (p_.eta_scale / average(r_u_))).max_component());
    sampler_.set_dimension(dim + kRouletteDimension);
    if (sampler_.next_float() >= survive) return false;
    p_.beta *= 1.0f / survive;
    return true;
  }

  // ---- light samples ----

  // One light sample from a scattering vertex (next event estimation): the world's light sampler's choice (a light
  // or one triangle of a mesh light), a point on it, the transmittance to it; `connect` evaluates the vertex towards
  // the light (empty: no contribution).
  template <typename Connect>
  void add_direct_light(const LightQuery& q, uint32_t dim, Connect&& connect) {
    sampler_.set_dimension(dim + kLightChoiceDimension);
    const auto chosen = w_.light_sampler.sample(q, sampler_.next_float_if(w_.light_sampler.chooses()));
    const Vec2f u = sampler_.next_2d();
    if (!chosen) return;
    const auto ls = sample_li(w_.lights[chosen->light], chosen->part, q, u);
    if (!ls || !(ls->pdf > 0.0f) || ls->li.is_black()) return;
    const std::optional<LightConnection> lc = connect(*ls);
    if (!lc || lc->f.is_black()) return;
    Rgb t_ray(1.0f), r_u(1.0f), r_l(1.0f);
    if (!transmittance(lc->shadow, lc->medium, t_ray, r_u, r_l)) return;
    r_l *= r_u_ * (ls->pdf * chosen->pmf);
    r_u *= r_u_ * lc->scatter_pdf;
    const float denominator = average(ls->delta || !s_.mis ? r_l : r_l + r_u);
    if (denominator > 0.0f) L_ += p_.beta * lc->f * t_ray * ls->li / denominator;
  }

  // Transmittance along a shadow ray (ray.d = the light's point - origin, ray.tmax just short of 1), crossing
  // medium boundaries; false when an opaque surface blocks it or its estimate reaches zero. t_ray multiplies in the
  // ratio-tracking estimate, r_u and r_l the channels' densities for direction and light sampling.
  bool transmittance(Ray ray, int medium, Rgb& t_ray, Rgb& r_u, Rgb& r_l) {
    const Vec3f target = ray.o + ray.d;
    for (int crossed = 0; crossed < kMaxSegments; ++crossed) {
      Hit hit;
      const bool found = query_shadow_hit(w_, ray, hit, c_);
      if (found) {
        const int material = w_.shape_data[hit.shape].material;
        if (material < 0 || !w_.materials[size_t(material)].passes_through) return false;
      }
      if (medium >= 0) {
        const float len = length(ray.d);
        const Ray unit{ray.o, ray.d / len, 0.0f, kInfinity, ray.time};
        if (!ratio_track(unit, (found ? hit.t : ray.tmax) * len, medium, t_ray, r_u, r_l)) return false;
      }
      if (!found) return true;
      const SurfaceInteraction si = make_interaction<kMeshesOnly>(w_, ray, hit);
      const MediumInterface& sides = w_.shape_data[hit.shape].media;
      if (sides.transition()) medium = sides.entered(ray.d, si.ng);
      ray = spawn_ray_to(si.p, si.ng, target, ray.time, si.extent);
    }
    return false;
  }

  bool ratio_track(const Ray& ray, float tmax, int medium, Rgb& t_ray, Rgb& r_u, Rgb& r_l) {
    ++c_.media.rays;
    const Rgb t_end = sample_collisions(
        w_.media[size_t(medium)], ray, tmax, rng_.next_float(), rng_, hero_,
        [&](Vec3f, const MediumProperties& mp, Rgb sigma_maj, Rgb t_maj) {
          count_collision(mp, sigma_maj);
          const Rgb sigma_n = clamp_zero(sigma_maj - mp.sigma_a - mp.sigma_s);
          const float pdf = t_maj[hero_] * sigma_maj[hero_];
          t_ray *= t_maj * sigma_n / pdf;
          r_l *= t_maj * sigma_maj / pdf;
          r_u *= t_maj * sigma_n / pdf;
          const float denominator = average(r_l + r_u);
          if (denominator > 0.0f && (t_ray / denominator).max_component() < kShadowRouletteBelow) {
            if (rng_.next_float() < kShadowRouletteEnd) t_ray = Rgb(0.0f);
            else t_ray *= 1.0f / (1.0f - kShadowRouletteEnd);
          }
          return !t_ray.is_black();
        });
    if (t_ray.is_black() || !(t_end[hero_] > 0.0f)) return false;
    const Rgb ratio = t_end / t_end[hero_];
    t_ray *= ratio;
    r_u *= ratio;
    r_l *= ratio;
    return true;
  }

  const RenderContext& ctx_;
  const World& w_;
  const PathSettings& s_;
  Sampler& sampler_;
  RayCounters& c_;
  const bool use_nee_;
  const int max_depth_;
  int hero_ = 0;
  Rng rng_;  // tracking decisions past each segment's first collision

  PathState p_;      // the ray, throughput beta, eta scale and whether the last bounce was specular
  int medium_ = -1;  // the medium p_.ray travels in (index into World::media), -1: vacuum
  Rgb L_{0.0f}, r_u_{1.0f}, r_l_{1.0f};
  int depth_ = 0;          // real scattering events so far
  LightQuery prev_{};      // the last scattering vertex, for the density with which NEE would have found an emitter
};

}  // namespace

Rgb integrate(const RenderContext& ctx, const VolPathSettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
              RayCounters& c, VisibleSurface* visible) {
  return dispatch_on_features(ctx.settings.features, [&]<bool kDelta, bool kDielectric, bool kMeshesOnly>() {
    VolumetricPath<kDelta, kDielectric, kMeshesOnly> path(ctx, s.path, sampler, c);
    return path.trace(ray, s.camera_medium, film, visible);
  });
}

}  // namespace kiln
