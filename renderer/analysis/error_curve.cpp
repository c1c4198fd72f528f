#include "renderer/analysis/error_curve.h"

#include <cstdio>

#include "core/error.h"

namespace kiln {

ErrorCurve render_error_curve(const World& world, const Camera& camera, const IntegratorSettings& settings,
                              const RenderOptions& options, uint32_t max_spp, const Image& reference,
                              const ProgressiveOptions& progressive, Film& film) {
  if (reference.width() != camera.width() || reference.height() != camera.height())
    throw Error("reference image is " + std::to_string(reference.width()) + "x" + std::to_string(reference.height()) +
                " but the camera renders " + std::to_string(camera.width()) + "x" + std::to_string(camera.height()));
  ErrorCurve curve;
  ProgressiveOptions measured = progressive;
  measured.on_wave = [&](const WaveReport& w) {
    curve.waves.push_back(MeasuredWave{w, error_stats(film.mean(), reference)});
    if (progressive.on_wave) progressive.on_wave(w);
  };
  curve.render = render_progressive(world, camera, settings, options, max_spp, measured, film);
  curve.final_error = curve.waves.empty() ? error_stats(film.mean(), reference) : curve.waves.back().error;
  return curve;
}

std::string wave_csv_header() { return "spp,seconds,mse,relmse,rmse\n"; }

std::string wave_csv_line(const MeasuredWave& w) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%u,%.6g,%.6g,%.6g,%.6g\n", w.wave.spp, w.wave.seconds, w.error.mse,
                w.error.rel_mse, w.error.rmse);
  return buf;
}

}  // namespace kiln
