// Integrators: the course's direct-lighting (Whitted-style) ray tracer and the path tracer. Both are pure
// functions of (world, camera ray, per-sample RNG), so output is independent of threads and tile order.
#pragma once
#include <cstdint>
#include <string>

#include "core/rng.h"
#include "renderer/world.h"

namespace kiln {

enum class DirectionSampling { Uniform, Cosine, Brdf };

struct IntegratorSettings {
  RendererKind kind = RendererKind::PathTracing;
  DirectionSampling directions = DirectionSampling::Brdf;
  bool nee = true;
  bool mis = true;                // combine NEE and BRDF sampling with the power heuristic (needs nee)
  bool russian_roulette = true;
  bool course_roulette = false;   // course semantics: roulette replaces the depth cap (spec §11)
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

// Radiance along a camera ray.
Rgb trace_direct(const World& world, const IntegratorSettings& s, const Ray& ray, Rng& rng, RayCounters& c);
Rgb trace_path(const World& world, const IntegratorSettings& s, const Ray& ray, Rng& rng, RayCounters& c);

inline Rgb trace(const World& world, const IntegratorSettings& s, const Ray& ray, Rng& rng, RayCounters& c) {
  return s.kind == RendererKind::PathTracing ? trace_path(world, s, ray, rng, c) : trace_direct(world, s, ray, rng, c);
}

}  // namespace kiln
