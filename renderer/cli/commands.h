// The kiln subcommands, callable from main() and from tests.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "renderer/accel/accelerator.h"
#include "renderer/render/render.h"
#include "renderer/integrators/rules.h"

namespace kiln {

struct RenderArgs {
  std::string scene;
  std::string out_dir = "out";
  std::optional<std::string> camera;  // camera id; all cameras when absent
  std::optional<uint32_t> spp;
  int threads = 0;                    // 0: all cores
  uint64_t seed = 0;
  std::optional<std::string> stats_path;
  bool quiet = false;
  AccelKind accel = AccelKind::Embree;
  RuleOverrides rules;  // --rules, --strategy, --rr, --max-depth, --course-roulette, --physical-lights, --clamp
  bool all_features = false;
  int subdivide = -1;
  bool reverse_tiles = false;
  std::optional<std::string> crop;       // "x0,x1,y0,y1"
  std::optional<std::string> spp_range;  // "FIRST:LAST" (absolute sample indices, LAST exclusive)
  std::optional<std::string> aovs;       // "albedo,normal,depth,position,variance"
  std::optional<double> time_limit;      // seconds
  std::optional<std::string> reference;  // EXR to report error against after every doubling of spp
  std::optional<std::string> filter;     // "NAME[:WIDTH]" (renderer/film/pixel_filter.h); else the scene's, else box
  std::optional<float> adaptive;         // adaptive sampling threshold (renderer/film/adaptive_sampling.h)
  uint32_t adaptive_min_spp = 0;         // 0: Cycles' automatic minimum
};

int cmd_render(const RenderArgs& args);
// overrides: --rules and --light-sampler.
int cmd_info(const std::string& scene_path, int subdivide, const RuleOverrides& overrides);
// Prints block-luminance statistics and MSE / relMSE of image against reference (both EXR) as JSON.
int cmd_compare(const std::string& image, const std::string& reference, int block);

// Shoots camera, bounce and shadow rays through Embree and the in-house BVH and compares them ray by ray; prints
// a JSON summary and returns 1 when disagreements exceed the budget.
int cmd_check_bvh(const std::string& scene_path, size_t rays, uint64_t seed);

// Merges partial renders into one EXR (see renderer/render/merge.h).
int cmd_merge(const std::vector<std::string>& parts, const std::string& output);

// Runs fn, mapping kiln::Error (bad input) to a one-line message and exit code 2.
int run_guarded(const std::function<int()>& fn);

}  // namespace kiln
