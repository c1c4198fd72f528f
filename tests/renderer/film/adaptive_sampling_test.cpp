// Adaptive sampling (renderer/film/adaptive_sampling.h): Cycles' per-pixel error estimate and schedule, decided from each
// pixel's own samples, so renders stay bit-identical for any thread count, tile order and wave split; pixels stop
// only below the threshold, and the ones that stop have the error the threshold asks for against a reference.
#include "renderer/film/adaptive_sampling.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <optional>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"

namespace kiln::test {
namespace {

// Why: the same threshold must mean what it means in Cycles (the race compares the two at equal thresholds).
TEST(Adaptive, ErrorAndScheduleAreCycles) {
  PixelSum p;
  p.n = 32;
  p.r = 8.0, p.g = 4.0, p.b = 2.0;
  p.even_r = 3.0, p.even_g = 2.5, p.even_b = 1.0;  // A = 6, 5, 2
  const double expected = (2.0 + 1.0 + 0.0) / 32.0 / (1e-4 + std::sqrt(14.0 / 32.0));
  EXPECT_DOUBLE_EQ(AdaptiveSampling::error(p), expected);
  AdaptiveSampling a;
  a.threshold = float(expected / 5.0) * 1.001f;
  EXPECT_TRUE(a.converged(p));
  a.threshold = float(expected / 5.0) * 0.999f;
  EXPECT_FALSE(a.converged(p));
  // Cycles' automatic minimum: threshold 0.1 -> 32, 0.01 -> 64, 0.001 -> 128 samples.
  EXPECT_EQ((AdaptiveSampling{0.1f, 0}.min_samples()), 32u);
  EXPECT_EQ((AdaptiveSampling{0.01f, 0}.min_samples()), 64u);
  EXPECT_EQ((AdaptiveSampling{0.001f, 0}.min_samples()), 128u);
  EXPECT_EQ((AdaptiveSampling{0.01f, 2}.min_samples()), 4u);
  // Tested after n samples when n % 16 == 0 and n - 1 > min (Cycles' need_filter of the 0-based index n - 1).
  const AdaptiveSampling c{0.01f, 0};
  for (uint32_t n : {16u, 32u, 48u, 64u, 65u, 79u, 81u}) EXPECT_FALSE(c.check_due(n)) << n;
  for (uint32_t n : {80u, 96u, 112u, 1024u}) EXPECT_TRUE(c.check_due(n)) << n;
}

struct AdaptiveRender {
  Film film;
  RenderStats stats;
};

class AdaptiveScene : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new SceneDesc(load_scene(std::string(KILN_SOURCE_DIR) + "/scenes/default.xml"));
    scene_->cameras[0].width = scene_->cameras[0].height = kSize;
    world_ = build_world(*scene_, {}).release();
  }
  static void TearDownTestSuite() {
    delete world_;
    delete scene_;
  }
  static AdaptiveRender render(float threshold, uint32_t spp, int threads, bool reverse,
                               const std::vector<std::pair<uint32_t, uint32_t>>& waves, uint64_t seed = 3) {
    std::optional<tbb::global_control> gc;
    if (threads > 0) gc.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
    const Camera cam(scene_->cameras[0]);
    const IntegratorSettings s = scene_settings(scene_->cameras[0], *scene_, world_->features);
    AdaptiveRender r{Film(cam.width(), cam.height()), {}};
    RenderOptions ro;
    ro.seed = seed;
    ro.spp_total = spp;
    ro.reverse_tile_order = reverse;
    if (threshold > 0) ro.adaptive = AdaptiveSampling{threshold, 16};
    for (const auto& [first, last] : waves) r.stats = render_samples(*world_, cam, s, ro, first, last, r.film);
    return r;
  }
  static constexpr int kSize = 16;
  static SceneDesc* scene_;
  static World* world_;
};
SceneDesc* AdaptiveScene::scene_ = nullptr;
World* AdaptiveScene::world_ = nullptr;

std::vector<uint32_t> counts(const Film& f) {
  std::vector<uint32_t> n;
  for (int y = 0; y < f.height(); ++y)
    for (int x = 0; x < f.width(); ++x) n.push_back(f.at(x, y).n);
  return n;
}

bool bit_identical(const Image& a, const Image& b) {
  return a.width() == b.width() && std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Rgb)) == 0;
}

// Why: a pixel's stopping decision may depend only on its own samples at fixed counts; any dependence on other
// pixels, on timing or on the wave boundaries shows up as a different image or different sample counts.
TEST_F(AdaptiveScene, BitIdenticalForThreadsTileOrderAndWaves) {
  const AdaptiveRender one = render(0.05f, 256, 1, false, {{0, 256}});
  const AdaptiveRender two = render(0.05f, 256, 2, true, {{0, 256}});
  const AdaptiveRender waves = render(0.05f, 256, 2, false, {{0, 16}, {16, 40}, {40, 100}, {100, 256}});
  EXPECT_TRUE(bit_identical(one.film.mean(), two.film.mean()));
  EXPECT_TRUE(bit_identical(one.film.mean(), waves.film.mean()));
  EXPECT_EQ(counts(one.film), counts(two.film));
  EXPECT_EQ(counts(one.film), counts(waves.film));
  // Adaptivity did something: some pixels stopped early, some ran to the maximum.
  const auto n = counts(one.film);
  EXPECT_LT(*std::min_element(n.begin(), n.end()), 256u);
  EXPECT_EQ(*std::max_element(n.begin(), n.end()), 256u);
}

// Why: pixels stop only when their estimate is below 5 * threshold, at a scheduled count; the others take every
// sample. And the estimate means what it says, in the image the render outputs (Film::mean, each pixel divided by
// its own sample count): against a 2048-spp reference, the pixels that stopped have a median true error (the same
// formula with the reference image in place of the even-sample mean) below 5 * threshold.
TEST_F(AdaptiveScene, StopsOnlyBelowTheThresholdAndReachesIt) {
  constexpr float kThreshold = 0.02f;
  constexpr uint32_t kMaxSpp = 1024;
  const AdaptiveRender a = render(kThreshold, kMaxSpp, 0, false, {{0, kMaxSpp}});
  const AdaptiveRender ref = render(0.0f, 2048, 0, false, {{0, 2048}}, 1000);
  const AdaptiveSampling rule{kThreshold, 16};
  const Image image = a.film.mean(), reference = ref.film.mean();
  std::vector<double> true_error;
  size_t stopped = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const PixelSum& p = a.film.at(x, y);
      if (!p.converged) {
        EXPECT_EQ(p.n, kMaxSpp) << x << "," << y;
        continue;
      }
      ++stopped;
      EXPECT_TRUE(rule.check_due(p.n)) << "stopped at an unscheduled count " << p.n;
      EXPECT_LT(AdaptiveSampling::error(p), kAdaptiveThresholdScale * kThreshold) << x << "," << y;
      const Rgb v = image.at(x, y), r = reference.at(x, y);
      const double diff = std::abs(v.r - r.r) + std::abs(v.g - r.g) + std::abs(v.b - r.b);
      true_error.push_back(diff / (1e-4 + std::sqrt(double(r.r) + r.g + r.b)));
    }
  ASSERT_GT(stopped, size_t(kSize * kSize / 4)) << "too few pixels stopped to judge the estimate";
  std::sort(true_error.begin(), true_error.end());
  const double median = true_error[true_error.size() / 2];
  std::printf("adaptive %g: %zu of %d pixels stopped early; true error of those: median %.4f, p90 %.4f (5 * threshold "
              "%.4f)\n", double(kThreshold), stopped, kSize * kSize, median, true_error[true_error.size() * 9 / 10],
              kAdaptiveThresholdScale * kThreshold);
  EXPECT_LT(median, kAdaptiveThresholdScale * kThreshold);
  // The image as a whole keeps the reference's scale (pixels that stopped early are not dimmed by the samples they
  // skipped): mean luminance within 4.5 standard errors of the reference's (the pixels' variances from the film).
  const auto image_mean = [](const Image& img, const Film& film) {
    const Image variance = film.variance_of_mean();
    double sum = 0, var = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        sum += img.at(x, y).luminance();
        var += variance.at(x, y).r;
      }
    const double n = double(kSize * kSize);
    return std::pair{sum / n, std::sqrt(var) / n};
  };
  const auto [m, se] = image_mean(image, a.film);
  const auto [m_ref, se_ref] = image_mean(reference, ref.film);
  std::printf("image mean luminance %.5f +- %.5f, reference %.5f +- %.5f\n", m, se, m_ref, se_ref);
  EXPECT_NEAR(m, m_ref, 4.5 * std::hypot(se, se_ref));
}

// Why: a render continuing a film whose pixels do not hold samples 0..first-1 cannot decide adaptively.
TEST_F(AdaptiveScene, RefusesToContinueFromTheMiddleOfTheSamples) {
  EXPECT_THROW(render(0.05f, 64, 1, false, {{8, 64}}), Error);
}

// Why: the CLI option reaches the scheduler and reports what it did; bad combinations are bad input (exit 2).
TEST(Adaptive, CommandLine) {
  const std::string dir = tmp_dir("adaptive_cli"), scene = std::string(KILN_SOURCE_DIR) + "/scenes/default.xml";
  std::filesystem::remove_all(dir + "/bad");
  auto [code, out] = run_kiln_command("render " + scene + " -q --spp 64 --crop 150,200,150,200 --adaptive 0.1 "
                              "--adaptive-min-spp 8 -o " + dir + "/out --stats " + dir + "/stats.json");
  ASSERT_EQ(code, 0) << out;
  const auto stats = nlohmann::json::parse(std::ifstream(dir + "/stats.json"));
  const auto& cam = stats["cameras"][0];
  EXPECT_LT(cam["mean_spp"].get<double>(), 64.0);
  EXPECT_GT(cam["adaptive"]["converged_fraction"].get<double>(), 0.0);
  EXPECT_EQ(cam["adaptive"]["min_spp"].get<int>(), 8);
  // The EXR has the scale of a render that took every sample (adaptive pixels divided by their own counts): mean
  // luminance over the crop within 5% (the noise of that mean is ~0.5%; a pixel divided by 64 instead of its count
  // would be dimmed by the mean spp's shortfall).
  std::tie(code, out) = run_kiln_command("render " + scene + " -q --spp 64 --crop 150,200,150,200 -o " + dir + "/full");
  ASSERT_EQ(code, 0) << out;
  const auto mean_luminance = [](const std::string& path) {
    double sum = 0;
    const Image img = read_exr(path).rgb;
    for (const Rgb& p : img.pixels()) sum += p.luminance();
    return sum / double(img.pixels().size());
  };
  const double adaptive = mean_luminance(dir + "/out/default.exr"), full = mean_luminance(dir + "/full/default.exr");
  EXPECT_NEAR(adaptive / full, 1.0, 0.05) << "adaptive " << adaptive << ", every sample " << full;
  std::tie(code, out) = run_kiln_command("render " + scene + " -q --spp 64 --adaptive 0.1 --spp-range 0:32 -o " + dir + "/bad");
  EXPECT_EQ(code, kExitBadInput) << out;
  EXPECT_NE(out.find("--adaptive"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bad"));
  std::tie(code, out) = run_kiln_command("render " + scene + " -q --spp 4 --filter lanczos -o " + dir + "/bad");
  EXPECT_EQ(code, kExitBadInput) << out;
  EXPECT_NE(out.find("--filter"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bad"));
}

}  // namespace
}  // namespace kiln::test
