// Accelerator queries wrapped with counting and cycle timing (the share of render time spent in ray queries).
#pragma once
#include <x86intrin.h>

#include "renderer/integrator.h"

namespace kiln {

inline bool query_intersect(const World& w, const Ray& r, Hit& hit, RayCounters& c, uint64_t& counter) {
  const uint64_t t0 = __rdtsc();
  const bool h = w.accel->intersect(r, hit);
  c.query_cycles += __rdtsc() - t0;
  ++counter;
  return h;
}

inline bool query_occluded(const World& w, const Ray& r, RayCounters& c) {
  const uint64_t t0 = __rdtsc();
  const bool o = w.accel->occluded(r);
  c.query_cycles += __rdtsc() - t0;
  ++c.shadow;
  return o;
}

}  // namespace kiln
