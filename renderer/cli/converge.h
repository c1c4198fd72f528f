// `kiln converge`: error against run time for several strategies on one scene (renderer/analysis/convergence.h). Writes
// DIR/convergence.csv, DIR/convergence.svg (log-log relMSE against seconds), DIR/reference.exr when it had to
// render the reference itself, and prints the strategies ranked by efficiency on stdout.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "renderer/accel/accelerator.h"

namespace kiln {

struct ConvergeArgs {
  std::string scene;
  std::optional<std::string> camera;     // camera id; the scene's first camera when absent
  std::optional<std::string> reference;  // EXR of the same (scaled) resolution; rendered with mis when absent
  std::string strategies = "uniform,cosine,brdf,nee,nee+rr,mis,mis+rr";
  // Light samplers (power, uniform, bvh), each strategy measured with each, named STRATEGY/SAMPLER; empty: the
  // scene's default sampler only, strategies named as given.
  std::string light_samplers;
  // The study's whole render time, the reference included when it is rendered here (renderer/analysis/convergence_budget.h).
  double budget_seconds = 60;
  int runs = 3;                          // independent runs per strategy (different seeds) for the spread
  std::string out_dir = "converge";
  double resolution_scale = 1.0;         // e.g. 0.25 renders 512x512 cameras at 128x128
  // Exactly this many spp for the rendered reference; absent: as many as fit its share of the budget (at most 4096).
  std::optional<uint32_t> reference_spp;
  uint32_t max_spp = 1u << 16;
  uint64_t seed = 0;
  int threads = 0;                       // 0: all cores
  AccelKind accel = AccelKind::Embree;
  // Point, spot, directional and (invisible) area lights cannot be found by direction sampling, so strategies
  // without NEE would converge to a different image; they are removed unless this is set.
  bool keep_delta_lights = false;
  bool quiet = false;
};

// Returns 0, or 130 when interrupted (partial results are still written). Throws kiln::Error on bad input.
int cmd_converge(const ConvergeArgs& args);

}  // namespace kiln
