// Progressive rendering (renderer/render/progressive.h): the doubling wave schedule, equality with a one-shot render of
// the same samples, the time limit and cancellation; its error against an exact reference after every wave
// (renderer/analysis/error_curve.h).
#include <gtest/gtest.h>

#include <cstring>
#include <thread>

#include <tbb/task_arena.h>

#include "core/error.h"
#include "renderer/render_util.h"
#include "renderer/analysis/convergence.h"
#include "renderer/analysis/error_curve.h"
#include "renderer/render/progressive.h"

namespace kiln::test {
namespace {

// The furnace box with a depth cap has an exact, constant image: Le * sum_{k=0..D} a^k.
constexpr float kAlbedo = 0.5f;
constexpr int kDepth = 3;
constexpr double kFurnaceValue = 1.0 + 0.5 + 0.25 + 0.125;

struct Furnace {
  SceneDesc scene;
  std::unique_ptr<World> world;
  IntegratorSettings settings;
  explicit Furnace(int res) : scene(furnace_box(kAlbedo, Rgb(1.0f))) {
    scene.cameras[0].width = scene.cameras[0].height = res;
    world = build_world(scene, {});
    PathSettings p;
    p.max_depth = kDepth;
    p.russian_roulette = false;
    p.directions = DirectionSampling::Uniform;  // cosine sampling would be exact here (zero variance)
    p.nee = p.mis = false;
    settings = p;
  }
  Image exact() const {
    const CameraDesc& c = scene.cameras[0];
    Image img(c.width, c.height);
    for (Rgb& p : img.pixels()) p = Rgb(float(kFurnaceValue));
    return img;
  }
};

TEST(Progressive, WaveScheduleDoubles) {
  const uint32_t want[][2] = {{0, 1}, {1, 2}, {2, 4}, {4, 8}, {8, 10}, {10, 10}};
  for (uint32_t k = 0; k < 6; ++k) {
    const WaveRange r = wave_range(k, 10);
    EXPECT_EQ(r.first, want[k][0]) << "wave " << k;
    EXPECT_EQ(r.last, want[k][1]) << "wave " << k;
  }
  EXPECT_EQ(wave_range(1, 1).first, wave_range(1, 1).last);  // 1 spp: wave 0 only
  EXPECT_EQ(wave_range(31, 0xffffffffu).first, 1u << 30);
  EXPECT_EQ(wave_range(32, 0xffffffffu).last, 0xffffffffu);
  EXPECT_EQ(wave_range(40, 0xffffffffu).first, wave_range(40, 0xffffffffu).last);  // no overflow
}

TEST(Progressive, PredictsTheNextWaveFromTimePerSample) {
  WaveReport w;
  w.wave = 3;  // samples [4, 8): 4 samples in 2 s
  w.wave_seconds = 2.0;
  EXPECT_DOUBLE_EQ(predict_next_wave_seconds(w, 1000), 4.0);  // next: [8, 16), 8 samples
  EXPECT_DOUBLE_EQ(predict_next_wave_seconds(w, 10), 1.0);    // next: [8, 10), 2 samples
  EXPECT_DOUBLE_EQ(predict_next_wave_seconds(w, 8), 0.0);     // nothing left
}

// The waves add exactly the samples a one-shot render of [0, max_spp) adds (with the same jittered pixel
// positions), so a progressive render is as reproducible as a plain one.
TEST(Progressive, WavesMatchAOneShotRenderBitForBit) {
  for (const RuleCase& rc : default_scene_rule_cases(24)) {
    SCOPED_TRACE(rc.name);
    const SceneDesc& scene = rc.scene;
    const auto world = build_world(scene, {});
    const IntegratorSettings s = scene_settings(scene.cameras[0], scene, world->features);
    const Camera cam(scene.cameras[0]);
    RenderOptions ro;
    ro.seed = 9;
    Film waves(cam.width(), cam.height());
    std::vector<uint32_t> seen;
    ProgressiveOptions po;
    po.on_wave = [&](const WaveReport& w) { seen.push_back(w.spp); };
    const ProgressiveResult res = render_progressive(*world, cam, s, ro, 12, po, waves);
    EXPECT_EQ(seen, (std::vector<uint32_t>{1, 2, 4, 8, 12}));
    EXPECT_EQ(res.spp, 12u);
    EXPECT_FALSE(res.stopped_by_time_limit);
    ASSERT_EQ(res.waves.size(), 5u);
    for (size_t i = 1; i < res.waves.size(); ++i) EXPECT_GE(res.waves[i].seconds, res.waves[i - 1].seconds);

    RenderOptions one = ro;
    one.spp_total = kProgressiveSppTotal;
    Film once(cam.width(), cam.height());
    render_samples(*world, cam, s, one, 0, 12, once);
    const Image a = waves.mean(), b = once.mean();
    EXPECT_EQ(std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Rgb)), 0);
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) ASSERT_EQ(waves.at(x, y).n, 12u);
  }
}

// Against an exact reference the MSE of an unbiased estimator with independent samples is variance / spp (log MSE
// against log spp has slope -1); the stratified sampler (core/sampler.h) completes a net with every doubling wave,
// so it must fall faster than that from the very first wave. A biased early wave (e.g. stratification that covers
// only part of each pixel) or a wrong sample count would flatten the line towards a plateau; a sampler that lost
// its stratification would give -1.
TEST(Progressive, ErrorFallsFasterThanOneOverSamples) {
  const Furnace f(32);
  const Camera cam(f.scene.cameras[0]);
  const Image exact = f.exact();
  Film film(cam.width(), cam.height());
  const ErrorCurve res = render_error_curve(*f.world, cam, f.settings, RenderOptions{}, 256, exact, {}, film);
  ASSERT_EQ(res.render.waves.size(), 9u);
  ASSERT_EQ(res.waves.size(), 9u);
  std::vector<double> spp, mse;
  for (const MeasuredWave& w : res.waves) {
    EXPECT_NEAR(w.error.rmse, std::sqrt(w.error.mse), 1e-12);
    spp.push_back(w.wave.spp);
    mse.push_back(w.error.mse);
  }
  const double slope = loglog_slope(spp, mse);
  EXPECT_LT(slope, -1.1);
  EXPECT_GT(slope, -2.0);
  // Every wave lowers the error, and MSE x spp (the per-sample variance for independent samples) only shrinks.
  for (size_t i = 1; i < mse.size(); ++i) EXPECT_LT(mse[i], mse[i - 1]) << "wave " << i;
  EXPECT_LT(mse.back() * spp.back(), mse.front() * spp.front());
  EXPECT_EQ(res.final_error.mse, mse.back());
  // The reported error is the film's.
  EXPECT_NEAR(error_stats(film.mean(), exact).rel_mse, res.final_error.rel_mse, 1e-15);
}

TEST(Progressive, TimeLimitStopsBeforeAnOverrunAndKeepsOneSample) {
  const Furnace f(16);
  const Camera cam(f.scene.cameras[0]);
  {
    // A budget nothing fits in still renders wave 0.
    ProgressiveOptions po;
    po.time_limit_seconds = 1e-9;
    Film film(cam.width(), cam.height());
    const ProgressiveResult res = render_progressive(*f.world, cam, f.settings, RenderOptions{}, 1u << 20, po, film);
    EXPECT_EQ(res.spp, 1u);
    EXPECT_TRUE(res.stopped_by_time_limit);
    EXPECT_EQ(film.at(3, 5).n, 1u);
  }
  {
    // Without the limit this would render 2^20 spp (minutes); with it, the render stops near the budget. The
    // bound is loose because the machine is shared: the prediction is only as good as the last wave's timing.
    constexpr double kBudget = 0.3;
    ProgressiveOptions po;
    po.time_limit_seconds = kBudget;
    Film film(cam.width(), cam.height());
    const auto t0 = std::chrono::steady_clock::now();
    const ProgressiveResult res = render_progressive(*f.world, cam, f.settings, RenderOptions{}, 1u << 20, po, film);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_TRUE(res.stopped_by_time_limit);
    EXPECT_GT(res.spp, 1u);
    EXPECT_LT(res.spp, 1u << 20);
    EXPECT_LT(wall, 4.0 * kBudget);
    EXPECT_LE(res.stats.seconds, wall);
  }
}

TEST(Progressive, CancelBetweenWavesKeepsCompleteWaves) {
  const Furnace f(16);
  const Camera cam(f.scene.cameras[0]);
  std::atomic<bool> cancel{false};
  RenderOptions ro;
  ro.cancel = &cancel;
  ProgressiveOptions po;
  po.on_wave = [&](const WaveReport& w) {
    if (w.spp == 4) cancel.store(true);
  };
  Film film(cam.width(), cam.height());
  const ProgressiveResult res = render_progressive(*f.world, cam, f.settings, ro, 64, po, film);
  EXPECT_TRUE(res.stats.cancelled);
  EXPECT_EQ(res.spp, 4u);
  EXPECT_EQ(res.waves.size(), 3u);
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) ASSERT_EQ(film.at(x, y).n, 4u);
}

// A SIGINT arriving in the middle of a wave: started pixels finish, the rest are skipped, and every pixel holds
// either the previous wave's count or the new one, so the film's mean is still a valid image. The cancel is set
// by the per-pixel test hook after two full waves and kPixelsIntoWave3 pixels of the third, on any thread count
// and any interleaving.
TEST(Progressive, CancelInsideAWaveLeavesAValidFilm) {
  constexpr int kRes = 48;
  constexpr int kPixels = kRes * kRes;
  constexpr int kPixelsIntoWave3 = 100;
  const Furnace f(kRes);
  const Camera cam(f.scene.cameras[0]);
  std::atomic<bool> cancel{false};
  std::atomic<int> pixels_done{0};
  RenderOptions ro;
  ro.cancel = &cancel;
  ro.tile_size = 4;
  // Every pixel past the mark sets the flag itself, so a thread that finishes one more pixel while the thread that
  // reached the mark has not stored yet still stops before its next pixel: at most one extra pixel per thread.
  ro.on_pixel_done = [&] {
    if (pixels_done.fetch_add(1) + 1 >= 2 * kPixels + kPixelsIntoWave3) cancel.store(true);
  };
  Film film(cam.width(), cam.height());
  const ProgressiveResult res = render_progressive(*f.world, cam, f.settings, ro, 1u << 20, ProgressiveOptions{}, film);
  ASSERT_TRUE(res.stats.cancelled);
  ASSERT_EQ(res.waves.size(), 3u);
  const WaveReport& last = res.waves.back();
  EXPECT_TRUE(last.cancelled);
  const uint32_t done = res.spp;
  EXPECT_EQ(done, 2u);        // waves 0 and 1: samples [0, 2)
  EXPECT_EQ(last.spp, done);  // the cancelled wave does not count as complete
  const WaveRange r = wave_range(last.wave, 1u << 20);
  int advanced = 0;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      const uint32_t n = film.at(x, y).n;
      ASSERT_TRUE(n == done || n == r.last) << "pixel " << x << "," << y << " has " << n << " samples";
      advanced += n == r.last;
    }
  // The pixels that reached the hook, plus at most one pixel in flight on each other thread.
  const int threads = tbb::this_task_arena::max_concurrency();
  EXPECT_GE(advanced, kPixelsIntoWave3);
  EXPECT_LE(advanced, kPixelsIntoWave3 + threads - 1);
  const Image img = film.mean();
  for (const Rgb& p : img.pixels()) ASSERT_TRUE(p.is_finite() && p.r > 0.0f);
}

TEST(Progressive, RejectsAReferenceOfAnotherSize) {
  const Furnace f(16);
  const Camera cam(f.scene.cameras[0]);
  const Image wrong(8, 16);
  Film film(cam.width(), cam.height());
  EXPECT_THROW(render_error_curve(*f.world, cam, f.settings, RenderOptions{}, 4, wrong, {}, film), Error);
}

TEST(Progressive, CsvLines) {
  EXPECT_EQ(wave_csv_header(), "spp,seconds,mse,relmse,rmse\n");
  MeasuredWave w;
  w.wave.spp = 16;
  w.wave.seconds = 1.5;
  w.error = ErrorStats{0.25, 0.5, 0.125};
  EXPECT_EQ(wave_csv_line(w), "16,1.5,0.25,0.125,0.5\n");
}

}  // namespace
}  // namespace kiln::test
