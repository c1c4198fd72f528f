// Accelerator queries wrapped with counting and cycle timing (the share of render time spent in ray queries).
#pragma once
#include <x86intrin.h>

#include "renderer/integrator.h"

namespace kiln {

// TSC ticks per second, measured once against the steady clock: converts the query cycles counted below into
// seconds (the ray-query time share of `kiln render`, the per-kind query rates of `kiln profile`).
double tsc_frequency();

// A camera ray when `primary`, else an indirect (bounce) ray.
inline bool query_intersect(const World& w, const Ray& r, Hit& hit, RayCounters& c, bool primary) {
  const uint64_t t0 = __rdtsc();
  const bool h = w.accel->intersect(r, hit);
  const uint64_t dt = __rdtsc() - t0;
  if (primary) {
    c.primary_cycles += dt;
    ++c.primary;
  } else {
    c.indirect_cycles += dt;
    ++c.indirect;
  }
  return h;
}

inline bool query_occluded(const World& w, const Ray& r, RayCounters& c) {
  const uint64_t t0 = __rdtsc();
  const bool o = w.accel->occluded(r);
  c.shadow_cycles += __rdtsc() - t0;
  ++c.shadow;
  return o;
}

}  // namespace kiln
