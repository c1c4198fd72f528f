// Progressive rendering in waves of doubling sample counts: wave 0 renders sample 0, wave k >= 1 renders samples
// [2^(k-1), 2^k) (the last wave capped at max_spp), so after wave k every pixel holds min(2^k, max_spp) samples.
// After each wave the caller hears how far the render got (renderer/analysis/error_curve.h measures the film against
// a reference there: the raw data of an error-against-time curve). With a time limit the next wave's cost is
// predicted from the previous wave's time per sample and the render stops before a wave that would overrun the
// budget (at least 1 spp is always rendered).
//
// Every prefix of waves must be an unbiased estimate of the pixel integral, so RenderOptions::spp_total is
// overridden with kProgressiveSppTotal: the course's 1-spp pixel-centre convention never applies. Nothing is lost to
// the waves: the sampler's points (core/sampler.h) make the first 2^k samples of every pixel a stratified net, which
// is exactly what each doubling wave completes.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "renderer/render/render.h"

namespace kiln {

// The stratification setting that makes render_samples jitter every sample over the whole pixel (render.cpp: a
// floor(sqrt(2)) = 1 stratum grid, then plain jitter).
inline constexpr uint32_t kProgressiveSppTotal = 2;

struct WaveReport {
  uint32_t wave = 0;          // 0-based wave index
  uint32_t spp = 0;           // samples per pixel after this wave (complete waves only)
  double seconds = 0;         // render time so far (sum of the waves' render_samples time; nothing the caller does)
  double wave_seconds = 0;    // this wave's render time
  bool cancelled = false;     // the wave was interrupted: pixels hold different sample counts
};

struct ProgressiveOptions {
  std::optional<double> time_limit_seconds;        // wall-clock budget for the whole progressive render
  std::function<void(const WaveReport&)> on_wave;  // called after every wave (also a cancelled one); counts against
                                                   // the time limit
};

struct ProgressiveResult {
  RenderStats stats;                   // merged over the waves; seconds = total render time
  uint32_t spp = 0;                    // samples per pixel of the last complete wave
  std::vector<WaveReport> waves;
  bool stopped_by_time_limit = false;  // stopped before max_spp because the next wave would overrun the budget
};

// Renders up to max_spp samples per pixel into film (which must be empty and of the camera's size) in doubling
// waves. Honours options.cancel between and inside waves; a cancelled wave leaves a valid film (Film keeps
// per-pixel counts).
ProgressiveResult render_progressive(const World& world, const Camera& camera, const IntegratorSettings& settings,
                                     const RenderOptions& options, uint32_t max_spp,
                                     const ProgressiveOptions& progressive, Film& film);

// The sample range [first, last) of wave k for a render of max_spp samples; empty (first == last) past the end.
struct WaveRange {
  uint32_t first = 0, last = 0;
};
WaveRange wave_range(uint32_t wave, uint32_t max_spp);

// Predicted render time of the wave after `done`: (its sample count) x (time per sample of `done`).
double predict_next_wave_seconds(const WaveReport& done, uint32_t max_spp);

}  // namespace kiln
