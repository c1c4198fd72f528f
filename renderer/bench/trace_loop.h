// The timed loop shared by the accelerator benchmarks: every ray of one kind through one accelerator per iteration,
// with the Mrays/s, hit-rate and kind reported the same way everywhere.
#pragma once
#include <benchmark/benchmark.h>

#include <vector>

#include "renderer/accel/accelerator.h"

namespace kiln {

// kind: 0 primary (coherent), 1 bounce (incoherent), 2 shadow (occlusion queries).
inline void trace_rays_benchmark(benchmark::State& state, const Accelerator& acc, const std::vector<Ray>& rays,
                                 int kind) {
  size_t hits = 0;
  for (auto _ : state) {
    for (const Ray& r : rays) {
      if (kind == 2) {
        hits += acc.occluded(r);
      } else {
        Hit h;
        hits += acc.intersect(r, h);
      }
    }
  }
  benchmark::DoNotOptimize(hits);
  const double traced = double(rays.size()) * double(state.iterations());
  state.counters["Mrays/s"] = benchmark::Counter(traced * 1e-6, benchmark::Counter::kIsRate);
  state.counters["hit%"] = traced > 0 ? 100.0 * double(hits) / traced : 0.0;
  state.counters["rays"] = double(rays.size());
  state.SetLabel(kind == 0 ? "primary" : kind == 1 ? "bounce" : "shadow");
}

}  // namespace kiln
