// Error against run time: a progressive render (renderer/render/progressive.h) whose film is measured against a
// reference image after every wave, and the CSV `kiln render --reference` writes from it.
#pragma once
#include <string>
#include <vector>

#include "core/image.h"
#include "renderer/analysis/image_compare.h"
#include "renderer/render/progressive.h"

namespace kiln {

struct MeasuredWave {
  WaveReport wave;
  ErrorStats error;  // of the film after this wave (also a cancelled one) against the reference
};

struct ErrorCurve {
  ProgressiveResult render;
  std::vector<MeasuredWave> waves;  // one per wave of render.waves
  ErrorStats final_error;           // of the final film (also when no wave ran)
};

// render_progressive with the film's error against reference measured after every wave (before
// progressive.on_wave hears of it; the measuring counts against the time limit, not in WaveReport::seconds).
// Throws kiln::Error when the reference's size differs from the camera's.
ErrorCurve render_error_curve(const World& world, const Camera& camera, const IntegratorSettings& settings,
                              const RenderOptions& options, uint32_t max_spp, const Image& reference,
                              const ProgressiveOptions& progressive, Film& film);

// One line per wave, "spp,seconds,mse,relmse,rmse"; lines end in '\n'.
std::string wave_csv_header();
std::string wave_csv_line(const MeasuredWave& w);

}  // namespace kiln
