#include "renderer/render/render.h"

#include <tbb/parallel_for.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <mutex>

#include "core/error.h"
#include "renderer/film/pixel_filter.h"

namespace kiln {
namespace {

struct Tile {
  int x0, y0, x1, y1;
};

// Pixel sample offset from the pixel centre and its filter weight: the pixel filter's importance sample from the
// sampler's first dimension, stratified over the pixel's samples; the centre when the rules sample a single-sample
// render there (the course's convention).
FilterSample pixel_offset(const IntegratorSettings& settings, uint32_t spp_total, const PixelFilter& filter,
                          Sampler& sampler) {
  sampler.set_dimension(kPixelDimension);
  return settings.centre_single_sample && spp_total <= 1 ? FilterSample{} : filter.sample(sampler.next_2d());
}

class Progress {
 public:
  // Only drawn on a terminal: a redirected stderr (CI logs) gets the final summary line alone.
  Progress(bool enabled, size_t total) : enabled_(enabled && ::isatty(2)), total_(total), start_(clock::now()) {}
  void tile_done() {
    if (!enabled_) return;
    const size_t done = ++done_;
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;
    const double t = std::chrono::duration<double>(clock::now() - start_).count();
    if (done != total_ && t - last_ < 0.25) return;
    last_ = t;
    const double frac = double(done) / double(total_);
    const double eta = frac > 0 ? t / frac - t : 0.0;
    const int bar = int(frac * 30.0);
    std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %6.1fs  ETA %6.1fs", bar, "##############################",
                 30 - bar, "", 100.0 * frac, t, eta);
    if (done == total_) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

 private:
  using clock = std::chrono::steady_clock;
  bool enabled_;
  size_t total_;
  std::atomic<size_t> done_{0};
  std::mutex mutex_;
  clock::time_point start_;
  double last_ = -1.0;
};

}  // namespace

RenderStats render_samples(const World& world, const Camera& camera, const IntegratorSettings& settings,
                           const RenderOptions& options, uint32_t first, uint32_t last, Film& film) {
  const auto start = std::chrono::steady_clock::now();
  Crop crop = options.crop.value_or(Crop{0, camera.width(), 0, camera.height()});
  std::vector<Tile> tiles;
  const int ts = std::max(1, options.tile_size);
  for (int y = crop.y0; y < crop.y1; y += ts)
    for (int x = crop.x0; x < crop.x1; x += ts)
      tiles.push_back(Tile{x, y, std::min(x + ts, crop.x1), std::min(y + ts, crop.y1)});
  if (options.reverse_tile_order) std::reverse(tiles.begin(), tiles.end());

  // Adaptive sampling decides from a pixel's samples 0..n-1, so every pixel must continue where it stopped.
  if (options.adaptive)
    for (int y = crop.y0; y < crop.y1; ++y)
      for (int x = crop.x0; x < crop.x1; ++x)
        if (const PixelSum& p = film.at(x, y); !p.converged && p.n != first)
          throw Error("adaptive sampling: pixel " + std::to_string(x) + "," + std::to_string(y) + " holds " +
                      std::to_string(p.n) + " samples but the render starts at sample " + std::to_string(first) +
                      " (adaptive renders cannot be split into sample ranges)");
  const PixelFilter filter(options.filter);
  const RenderContext ctx(world, camera, settings, options, film);
  const bool surfaces = film.keeps_surfaces();  // the integrators record what each sample saw only when asked
  std::vector<RenderStats> tile_stats(tiles.size());
  Progress progress(options.progress, tiles.size());
  // One task per tile; work stealing balances uneven tiles.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t ti = range.begin(); ti != range.end(); ++ti) {
      if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
        tile_stats[ti].cancelled = true;
        continue;
      }
      const Tile& t = tiles[ti];
      RenderStats& st = tile_stats[ti];
      st.rays.timed = options.time_ray_queries;
      for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) {
          // Checked per pixel, not per tile: at high spp one tile can take minutes, and an interrupt must stop
          // promptly. Pixels keep their own sample counts, so a partly rendered tile is still a valid image.
          if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
            st.cancelled = true;
            break;
          }
          PixelSum& px = film.at(x, y);
          // The pixel's place on the whole image (a crop keeps it): a background texture is looked up at the pixel
          // centre, the same for every sample of the pixel.
          const Vec2f film_position = pixel_film_position(x, y, camera.width(), camera.height());
          for (uint32_t s = first; s < last && !px.converged; ++s) {
            Sampler sampler(options.seed, uint32_t(x), uint32_t(y), s);
            const FilterSample fs = pixel_offset(settings, options.spp_total, filter, sampler);
            sampler.set_dimension(kLensDimension);
            // A pinhole reads no lens sample: it is not computed (the dimensions after it are fixed anyway).
            const Vec2f lens = camera.has_aperture() ? sampler.next_2d() : Vec2f(0.5f, 0.5f);
            // Only a scene with motion takes a time sample (from a dedicated stream: other values are unchanged).
            const float time = (settings.features & kFeatureMotionBlur) ? sampler.dedicated_1d(kTimeStream) : 0.0f;
            const CameraRay cr =
                camera.sample(float(x) + 0.5f + fs.offset.x, float(y) + 0.5f + fs.offset.y, lens, time);
            sampler.set_dimension(kFirstPathDimension);
            VisibleSurface visible;
            // A ray the lens blocks still counts as a sample, of no radiance (and sees no surface).
            Rgb L = cr.weight > 0.0f ? trace(ctx, cr.ray, film_position, sampler, st.rays, surfaces ? &visible : nullptr)
                                     : Rgb(0.0f);
            if (!L.is_finite() || L.has_negative()) {
              if (!st.has_nan) {
                st.has_nan = true;
                st.nan_x = x;
                st.nan_y = y;
                st.nan_sample = s;
              }
              ++st.rays.nan_samples;
              L = Rgb(0.0f);
            }
            // The camera's own weight (a realistic lens's transmission) scales the radiance, not what it saw.
            film.add_sample(x, y, s, camera.clamp_sample(L * cr.weight), fs.weight, visible);
            if (options.adaptive && options.adaptive->check_due(px.n)) px.converged = options.adaptive->converged(px);
          }
          if (options.on_pixel_done) options.on_pixel_done();
        }
      progress.tile_done();
    }
  });

  RenderStats total;
  for (const RenderStats& st : tile_stats) {
    total.rays.add(st.rays);
    total.cancelled |= st.cancelled;
    if (st.has_nan && (!total.has_nan || std::tie(st.nan_y, st.nan_x) < std::tie(total.nan_y, total.nan_x))) {
      total.has_nan = true;
      total.nan_x = st.nan_x;
      total.nan_y = st.nan_y;
      total.nan_sample = st.nan_sample;
    }
  }
  total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return total;
}

}  // namespace kiln
