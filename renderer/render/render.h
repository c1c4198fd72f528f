// Renders one camera: a TBB tile scheduler over the film, one integrator call per pixel sample.
#pragma once
#include <array>
#include <atomic>
#include <functional>
#include <optional>

#include "renderer/film/adaptive_sampling.h"
#include "renderer/world/camera.h"
#include "renderer/film/film.h"
#include "renderer/integrators/integrator.h"

namespace kiln {

struct Crop {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // pixel rectangle [x0, x1) x [y0, y1)
};

struct RenderOptions {
  uint64_t seed = 0;
  uint32_t spp_total = 1;    // the frame's nominal sample count (1 spp: pixel centres under the course's rules)
  int tile_size = 16;
  std::optional<Crop> crop;  // only these pixels are rendered (others stay empty)
  bool reverse_tile_order = false;     // for tests: the result must not depend on it
  bool progress = false;               // progress bar + ETA on stderr
  const std::atomic<bool>* cancel = nullptr;  // set asynchronously (SIGINT): finish started tiles, skip the rest
  PixelFilterDesc filter;                     // pixel filter, by filter importance sampling (default: box, 1 px)
  // Stop sampling a pixel once its noise estimate is below the threshold (renderer/film/adaptive_sampling.h). Needs
  // every pixel's samples from index 0 in this film: not for --spp-range parts.
  std::optional<AdaptiveSampling> adaptive;
  // Test hook: called after every pixel's samples (on the rendering thread), e.g. to cancel at a known point.
  std::function<void()> on_pixel_done;
};

struct RenderStats {
  RayCounters rays;
  double seconds = 0;
  bool cancelled = false;
  // The first non-finite sample in (y, x, sample) order, reported once.
  bool has_nan = false;
  int nan_x = 0, nan_y = 0;
  uint64_t nan_sample = 0;
};

// Adds samples [first, last) of every pixel (in the crop) to film.
RenderStats render_samples(const World& world, const Camera& camera, const IntegratorSettings& settings,
                           const RenderOptions& options, uint32_t first, uint32_t last, Film& film);

}  // namespace kiln
