// Integrators: the course's direct-lighting (Whitted-style) ray tracer and the path tracer. Both are pure
// functions of (world, camera ray, per-sample RNG), so output is independent of threads and tile order.
#pragma once
#include <cstdint>
#include <string>

#include "core/sampler.h"
#include "renderer/world.h"

namespace kiln {

enum class DirectionSampling { Uniform, Cosine, Brdf };

// How a CENG795 scene's RussianRoulette is rendered (README, "Course path-tracing semantics"). The course's
// roulette over-weights the direct light of vertex k by 2 - p_k (p_k: the survival probability it derives from
// the path's BRDF values). Expected renders that expectation with Kiln's unbiased throughput roulette, i.e. the
// same image with finite variance; Literal replays the course's own roulette (same expectation, its fireflies:
// survivors carry weights that grow like (pi/kd)^(k(k+1)/2), so its variance is unbounded).
enum class CourseRoulette { Off, Expected, Literal };

struct IntegratorSettings {
  RendererKind kind = RendererKind::PathTracing;
  DirectionSampling directions = DirectionSampling::Brdf;
  bool nee = true;
  bool mis = true;                // combine NEE and BRDF sampling with the power heuristic (needs nee)
  bool russian_roulette = true;
  CourseRoulette course_roulette = CourseRoulette::Off;  // course semantics: roulette replaces the depth cap
  bool split_delta = false;       // course rule: follow every Fresnel branch of mirror / glass (spec §11)
  int max_depth = 8;              // bounces after the camera ray; < 0: unlimited (only with roulette)
  int rr_min_depth = 3;           // Kiln's roulette starts after this many bounces
  bool nee_at_last_vertex = false;  // course rule: the vertex at max_depth still samples lights (README)
  float course_ray_epsilon = 0.0f;  // course ray tracer: ShadowRayEpsilon offset along the normal; 0 = ulp offset
  float clamp = 0.0f;             // firefly clamp on per-sample radiance; 0 = off (default)
  uint32_t features = kFeatureAll;  // the scene's feature mask; code paths for absent features are skipped
  std::string describe() const;
};

// Per-thread counters, merged per tile (no atomics on the hot path).
struct RayCounters {
  uint64_t primary = 0, shadow = 0, indirect = 0;
  // TSC cycles spent inside accelerator queries, by ray kind (the query rate of each kind inside a render).
  uint64_t primary_cycles = 0, shadow_cycles = 0, indirect_cycles = 0;
  uint64_t nan_samples = 0;
  void add(const RayCounters& o) {
    primary += o.primary;
    shadow += o.shadow;
    indirect += o.indirect;
    primary_cycles += o.primary_cycles;
    shadow_cycles += o.shadow_cycles;
    indirect_cycles += o.indirect_cycles;
    nan_samples += o.nan_samples;
  }
  uint64_t total() const { return primary + shadow + indirect; }
  uint64_t query_cycles() const { return primary_cycles + shadow_cycles + indirect_cycles; }
};

// Settings for a camera: the scene's Renderer/RendererParams, MaxRecursionDepth and Kiln's defaults.
IntegratorSettings settings_for_camera(const CameraDesc& camera, const SceneDesc& scene);

// Sampler dimensions (core/sampler.h): the pixel position and lens come first, then each path vertex takes the
// same kDimensionsPerVertex requests, so that a given request is stratified across the samples of a pixel.
inline constexpr uint32_t kPixelDimension = 0;
inline constexpr uint32_t kLensDimension = 1;
inline constexpr uint32_t kFirstPathDimension = 2;

// Radiance along a camera ray (the sampler is positioned at kFirstPathDimension).
Rgb trace_direct(const World& world, const IntegratorSettings& s, const Ray& ray, Sampler& sampler, RayCounters& c);
Rgb trace_path(const World& world, const IntegratorSettings& s, const Ray& ray, Sampler& sampler, RayCounters& c);

inline Rgb trace(const World& world, const IntegratorSettings& s, const Ray& ray, Sampler& sampler, RayCounters& c) {
  return s.kind == RendererKind::PathTracing ? trace_path(world, s, ray, sampler, c) : trace_direct(world, s, ray, sampler, c);
}

}  // namespace kiln
