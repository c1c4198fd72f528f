// Renders one camera: a TBB tile scheduler over the film, one integrator call per pixel sample.
#pragma once
#include "renderer/film/film.h"
#include "renderer/integrators/integrator.h"

namespace kiln {

struct RenderStats {
  RayCounters rays;
  double seconds = 0;
  bool cancelled = false;
  // The first non-finite sample in (y, x, sample) order, reported once.
  bool has_nan = false;
  int nan_x = 0, nan_y = 0;
  uint64_t nan_sample = 0;
};

// Adds samples [first, last) of every pixel (in the crop) to film. The render's context (camera, its pixel spread,
// settings, options, film) is made here; the world is only read, so renders of one world may run at once (into
// different films).
RenderStats render_samples(const World& world, const Camera& camera, const IntegratorSettings& settings,
                           const RenderOptions& options, uint32_t first, uint32_t last, Film& film);

}  // namespace kiln
