// Accelerator queries wrapped with counting and, when asked for (`kiln profile`), cycle timing: the two time-stamp
// reads around every query cost 1.4% of a diffuse scene's render, so a plain render leaves them out.
#pragma once
#include <x86intrin.h>

#include <cmath>
#include <cstdint>

#include "media/tracking.h"
#include "renderer/world/world.h"

namespace kiln {

// Per-thread counters, merged per tile (no atomics on the hot path).
struct RayCounters {
  uint64_t primary = 0, shadow = 0, indirect = 0;
  // TSC cycles spent inside accelerator queries, by ray kind (the query rate of each kind inside a render).
  uint64_t primary_cycles = 0, shadow_cycles = 0, indirect_cycles = 0;
  uint64_t nan_samples = 0;
  bool timed = false;  // the *_cycles are counted (RenderOptions::time_ray_queries)
  TrackingCounters media;  // the volumetric path tracer's tracking through media
  void add(const RayCounters& o) {
    primary += o.primary;
    shadow += o.shadow;
    indirect += o.indirect;
    primary_cycles += o.primary_cycles;
    shadow_cycles += o.shadow_cycles;
    indirect_cycles += o.indirect_cycles;
    nan_samples += o.nan_samples;
    media.add(o.media);
  }
  uint64_t total() const { return primary + shadow + indirect; }
  uint64_t query_cycles() const { return primary_cycles + shadow_cycles + indirect_cycles; }
};

// TSC ticks per second, measured once against the steady clock: converts the query cycles counted below into
// seconds (the ray-query time share of `kiln render`, the per-kind query rates of `kiln profile`).
double tsc_frequency();

// TSC cycles since t0 when the counters are timed, else 0 (and no time-stamp read).
inline uint64_t query_start(const RayCounters& c) { return c.timed ? __rdtsc() : 0; }
inline uint64_t query_cycles_since(const RayCounters& c, uint64_t t0) { return c.timed ? __rdtsc() - t0 : 0; }

// A camera ray when `primary`, else an indirect (bounce) ray.
inline bool query_intersect(const World& w, const Ray& r, Hit& hit, RayCounters& c, bool primary) {
  const uint64_t t0 = query_start(c);
  const bool h = w.accel->intersect(r, hit);
  const uint64_t dt = query_cycles_since(c, t0);
  if (primary) {
    c.primary_cycles += dt;
    ++c.primary;
  } else {
    c.indirect_cycles += dt;
    ++c.indirect;
  }
  return h;
}

// Bounds the triangles one camera ray may pass through under backface culling (a ray through a dense mesh from
// behind); past it the ray is taken to miss.
inline constexpr int kMaxCulledHits = 256;

// A camera ray under backface culling (the course's BackfaceCulling): triangles whose (v1-v0)x(v2-v0) normal faces
// away from the ray are passed through; spheres, closed and seen from outside, are never culled.
inline bool query_camera_culled(const World& w, const Ray& r, Hit& hit, RayCounters& c) {
  Ray ray = r;
  for (int i = 0; i < kMaxCulledHits; ++i) {
    if (!query_intersect(w, ray, hit, c, i == 0)) return false;
    if (w.geometry.shapes[hit.shape].kind == ShapeKind::Sphere || dot(hit.ng, ray.d) < 0.0f) return true;
    ray.tmin = std::nextafter(hit.t, kInfinity);
  }
  return false;
}

// A shadow ray that needs its closest hit: through participating media, where boundaries are crossed, not
// occluding (the volumetric path tracer's transmittance rays).
inline bool query_shadow_hit(const World& w, const Ray& r, Hit& hit, RayCounters& c) {
  const uint64_t t0 = query_start(c);
  const bool h = w.accel->intersect(r, hit);
  c.shadow_cycles += query_cycles_since(c, t0);
  ++c.shadow;
  return h;
}

inline bool query_occluded(const World& w, const Ray& r, RayCounters& c) {
  const uint64_t t0 = query_start(c);
  const bool o = w.accel->occluded(r);
  c.shadow_cycles += query_cycles_since(c, t0);
  ++c.shadow;
  return o;
}

}  // namespace kiln
