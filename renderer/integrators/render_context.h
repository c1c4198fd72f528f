// One render of a world: which camera, how it is sampled and where the samples go. The world is built once and never
// changed by a render (const everywhere); whatever belongs to one render travels here instead, so that two renders
// of one world (two cameras, two sample ranges) may run at once. render_samples (renderer/render/render.h) makes one
// per call and hands it to the integrators.
#pragma once
#include <atomic>
#include <functional>
#include <optional>

#include "renderer/film/adaptive_sampling.h"
#include "renderer/film/film.h"
#include "renderer/integrators/settings.h"
#include "renderer/world/camera.h"
#include "renderer/world/world.h"
#include "scenes/scene.h"

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
  bool time_ray_queries = false;       // count TSC cycles in accelerator queries (kiln profile's time shares)
  const std::atomic<bool>* cancel = nullptr;  // set asynchronously (SIGINT): finish started tiles, skip the rest
  PixelFilterDesc filter;                     // pixel filter, by filter importance sampling (default: box, 1 px)
  // Stop sampling a pixel once its noise estimate is below the threshold (renderer/film/adaptive_sampling.h). Needs
  // every pixel's samples from index 0 in this film: not for --spp-range parts.
  std::optional<AdaptiveSampling> adaptive;
  // Test hook: called after every pixel's samples (on the rendering thread), e.g. to cancel at a known point.
  std::function<void()> on_pixel_done;
};

// The integrators read the world, the settings and the camera's pixel spread; the film is the one place a render
// writes (each pixel by the one task that renders it), also what later records of a camera sample's first hit will
// be written to.
struct RenderContext {
  const World& world;
  const Camera& camera;
  CameraSpread pixel_spread;  // camera.pixel_spread(): texture footprints are measured in this camera's pixels
  float pbrt_footprint_scale;  // pbrt-v4 textures' footprints narrowed for the frame's spp (footprint_scale_for_spp)
  const IntegratorSettings& settings;
  const RenderOptions& options;
  Film& film;

  RenderContext(const World& w, const Camera& c, const IntegratorSettings& s, const RenderOptions& o, Film& f)
      : world(w),
        camera(c),
        pixel_spread(c.pixel_spread()),
        pbrt_footprint_scale(footprint_scale_for_spp(o.spp_total)),
        settings(s),
        options(o),
        film(f) {}
};

}  // namespace kiln
