#include "renderer/render/progressive.h"

#include <chrono>

namespace kiln {

WaveRange wave_range(uint32_t wave, uint32_t max_spp) {
  if (wave == 0) return {0, std::min(1u, max_spp)};
  if (wave > 32) return {max_spp, max_spp};
  const uint64_t first = uint64_t(1) << (wave - 1), last = std::min<uint64_t>(uint64_t(1) << wave, max_spp);
  if (first >= max_spp) return {max_spp, max_spp};
  return {uint32_t(first), uint32_t(last)};
}

double predict_next_wave_seconds(const WaveReport& done, uint32_t max_spp) {
  const WaveRange cur = wave_range(done.wave, max_spp), next = wave_range(done.wave + 1, max_spp);
  const uint32_t cur_n = cur.last - cur.first;
  if (cur_n == 0) return 0.0;
  return done.wave_seconds / double(cur_n) * double(next.last - next.first);
}

ProgressiveResult render_progressive(const World& world, const Camera& camera, const IntegratorSettings& settings,
                                     const RenderOptions& options, uint32_t max_spp,
                                     const ProgressiveOptions& progressive, Film& film) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  RenderOptions ro = options;
  ro.spp_total = kProgressiveSppTotal;

  ProgressiveResult result;
  max_spp = std::max(1u, max_spp);
  for (uint32_t wave = 0;; ++wave) {
    const WaveRange range = wave_range(wave, max_spp);
    if (range.first >= range.last) break;
    if (wave > 0 && progressive.time_limit_seconds) {
      const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
      if (elapsed + predict_next_wave_seconds(result.waves.back(), max_spp) > *progressive.time_limit_seconds) {
        result.stopped_by_time_limit = true;
        break;
      }
    }
    if (options.cancel && options.cancel->load()) {
      result.stats.cancelled = true;
      break;
    }
    const RenderStats rs = render_samples(world, camera, settings, ro, range.first, range.last, film);
    result.stats.rays.add(rs.rays);
    result.stats.seconds += rs.seconds;
    result.stats.cancelled |= rs.cancelled;
    if (rs.has_nan && !result.stats.has_nan) {
      result.stats.has_nan = true;
      result.stats.nan_x = rs.nan_x;
      result.stats.nan_y = rs.nan_y;
      result.stats.nan_sample = rs.nan_sample;
    }

    WaveReport w;
    w.wave = wave;
    w.cancelled = rs.cancelled;
    if (!rs.cancelled) result.spp = range.last;
    w.spp = result.spp;
    w.seconds = result.stats.seconds;
    w.wave_seconds = rs.seconds;
    result.waves.push_back(w);
    if (progressive.on_wave) progressive.on_wave(w);
    if (rs.cancelled) break;
  }
  return result;
}

}  // namespace kiln
