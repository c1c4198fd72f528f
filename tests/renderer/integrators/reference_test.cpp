// Kiln against the course's own reference renders (CENG795), with the acceptance statistics of issues 2-5:
// LDR scenes by the share of 8-bit pixels within a tolerance, HDR scenes by 32x32 block-luminance statistics
// (noise-aware: Monte Carlo scenes are rendered at fewer samples than the references, and blocks average the noise).
#include <gtest/gtest.h>

#include <cstdlib>

#include "renderer/render_util.h"
#include "renderer/analysis/image_compare.h"
#include "renderer/image_io/image_io.h"
#include "renderer/film/tonemap.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

std::string course(const std::string& rel) { return shared_dir() + "/scenes/ceng795/" + rel; }

// Renders one camera of a course scene the way `kiln render` does; spp 0 keeps the scene's NumSamples.
Image render_course_camera(const SceneDesc& scene, size_t camera, uint32_t spp) {
  const auto world = build_scene_world(scene);
  const CameraDesc& cd = scene.cameras.at(camera);
  return render_image(*world, cd, scene_settings(cd, scene, world->features),
                      spp ? spp : uint32_t(std::max(1, cd.num_samples)));
}

Image png_preview(const Image& img, const SceneDesc& scene, size_t camera) {
  const std::vector<uint8_t> ldr = to_ldr(img, preview_for_camera(scene.cameras[camera], scene));
  Image out(img.width(), img.height());
  for (size_t i = 0; i < out.pixels().size(); ++i)
    out.pixels()[i] = Rgb(ldr[3 * i] / 255.0f, ldr[3 * i + 1] / 255.0f, ldr[3 * i + 2] / 255.0f);
  return out;
}

size_t camera_named(const SceneDesc& s, const std::string& image_name) {
  for (size_t i = 0; i < s.cameras.size(); ++i)
    if (s.cameras[i].image_name == image_name) return i;
  ADD_FAILURE() << "no camera writes " << image_name;
  return 0;
}

#define REQUIRE_SHARED() KILN_NEED_SHARED_PATH(shared_dir() + "/scenes/ceng795")

// 8-bit agreement counted over the pixels lit (any channel above 0/255) in either image: the course scenes are
// mostly black background, which a black render would match too.
struct LitMatch {
  size_t lit = 0, matched = 0;
  double fraction() const { return lit ? double(matched) / double(lit) : 0.0; }
};
LitMatch lit_match(const Image& a, const Image& reference, int tol) {
  LitMatch m;
  if (a.width() != reference.width() || a.height() != reference.height()) return m;
  const auto byte = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  for (size_t i = 0; i < a.pixels().size(); ++i) {
    bool lit = false, close = true;
    for (int c = 0; c < 3; ++c) {
      const int x = byte(a.pixels()[i][c]), y = byte(reference.pixels()[i][c]);
      lit |= x > 0 || y > 0;
      close &= std::abs(x - y) <= tol;
    }
    m.lit += lit;
    m.matched += lit && close;
  }
  return m;
}

// Holds mine to >= min_fraction of the lit pixels within tol/255 of the reference, and prints the margin.
void expect_lit_match(const Image& mine, const Image& reference, int tol, double min_fraction, const std::string& name) {
  const LitMatch m = lit_match(mine, reference, tol);
  std::printf("[ ldr ] %s: %zu lit pixels, %.4f within %d/255 (limit %.2f)\n", name.c_str(), m.lit, m.fraction(), tol,
              min_fraction);
  EXPECT_GT(m.lit, 0u) << name;
  EXPECT_GE(m.fraction(), min_fraction) << name << ": " << m.matched << " of " << m.lit << " lit pixels";
}

// Block statistics, printed on success too so that CI logs show the margin to the limits.
BlockStats reported_block_stats(const Image& mine, const Image& reference, const std::string& name) {
  const BlockStats b = block_luminance_stats(mine, reference, 32);
  std::printf("[ hdr ] %s: %zu blocks, median %.4f, p95 %.4f, mean ratio %.4f\n", name.c_str(), b.blocks,
              b.median_rel, b.p95_rel, b.mean_ratio);
  EXPECT_EQ(b.left_out.image, 0u) << name << ": pixels that are not finite";
  return b;
}

// Issue 2: hw1_2021 LDR scenes, >= 99% of the lit pixels within 3/255 of the course PNG.
class Hw1Reference : public ::testing::TestWithParam<std::string> {};
TEST_P(Hw1Reference, MatchesCoursePng) {
  REQUIRE_SHARED();
  const SceneDesc scene = load_scene(course("regression/hw1_2021/" + GetParam() + ".xml"));
  const Image mine = png_preview(render_course_camera(scene, 0, 0), scene, 0);
  const Image ref = read_image(course("regression/hw1_2021/" + GetParam() + ".png"));
  expect_lit_match(mine, ref, 3, 0.99, GetParam());
}
INSTANTIATE_TEST_SUITE_P(Course, Hw1Reference,
                         ::testing::Values("simple", "two_spheres", "spheres", "cornellbox", "cornellbox_recursive",
                                           "bunny"));

// scienceTree's dielectric "Concrete" mesh is the case that pinned the course ray tracer's dielectric conventions
// (README, "Course ray tracer"): 96.9% of pixels within 3/255 before them.
TEST(Hw1Reference, ScienceTreeMatchesCoursePng) {
  REQUIRE_SHARED();
  const SceneDesc scene = load_scene(course("regression/hw1_2021/scienceTree.xml"));
  const Image mine = png_preview(render_course_camera(scene, 0, 0), scene, 0);
  expect_lit_match(mine, read_image(course("regression/hw1_2021/scienceTree.png")), 3, 0.99, "scienceTree");
}

// Issue 3: BRDF spheres, >= 99% of the lit pixels within 4/255 of the course PNG; the 2021 variants render.
class BrdfReference : public ::testing::TestWithParam<std::string> {};
TEST_P(BrdfReference, MatchesCoursePng) {
  REQUIRE_SHARED();
  const SceneDesc scene = load_scene(course("brdf/" + GetParam() + ".xml"));
  const Image mine = png_preview(render_course_camera(scene, 0, 0), scene, 0);
  expect_lit_match(mine, read_image(course("brdf/reference/" + GetParam() + ".png")), 4, 0.99, GetParam());
  const SceneDesc s2021 = load_scene(course("brdf_2021/" + GetParam() + ".xml"));
  const Image img2021 = render_course_camera(s2021, 0, 0);
  for (const Rgb& c : img2021.pixels()) ASSERT_TRUE(c.is_finite() && !c.has_negative());
}
INSTANTIATE_TEST_SUITE_P(Course, BrdfReference,
                         ::testing::Values("brdf_phong_original", "brdf_phong_modified", "brdf_phong_modified_normalized",
                                           "brdf_blinnphong_original", "brdf_blinnphong_modified",
                                           "brdf_blinnphong_modified_normalized", "brdf_torrancesparrow"));

// Issue 4: direct lighting against the course EXRs: block median < 3%, p95 < 10% (rendered at 16 of 100 spp).
constexpr uint32_t kDirectLightingTestSpp = 16;
class DirectLightingReference : public ::testing::TestWithParam<std::string> {};
TEST_P(DirectLightingReference, MatchesCourseExr) {
  REQUIRE_SHARED();
  const SceneDesc scene = load_scene(course("directLighting/" + GetParam() + ".xml"));
  const Image mine = render_course_camera(scene, 0, kDirectLightingTestSpp);
  const BlockStats b = reported_block_stats(mine, read_exr(course("directLighting/" + GetParam() + ".exr")).rgb, GetParam());
  EXPECT_LT(b.median_rel, 0.03);
  EXPECT_LT(b.p95_rel, 0.10);
}
INSTANTIATE_TEST_SUITE_P(Course, DirectLightingReference,
                         ::testing::Values("cornellbox_jaroslav_diffuse", "cornellbox_jaroslav_glossy",
                                           "cornellbox_jaroslav_diffuse_area", "cornellbox_jaroslav_glossy_area",
                                           "cornellbox_jaroslav_glossy_area_small",
                                           "cornellbox_jaroslav_glossy_area_sphere",
                                           "cornellbox_jaroslav_glossy_area_ellipsoid"));

// Issue 5: path-tracing cameras with NEE (the low-noise ones, so 32 spp suffice for the block statistics; the
// others are checked at full spp outside CI, see the issue notes).
struct PtCase {
  const char* scene;
  const char* image;
  bool roulette;
};
class PathTracingReference : public ::testing::TestWithParam<PtCase> {};
TEST_P(PathTracingReference, MatchesCourseExr) {
  REQUIRE_SHARED();
  const PtCase& c = GetParam();
  const SceneDesc scene = load_scene(course(std::string("pathTracing/cornellbox_jaroslav_path_") + c.scene + ".xml"));
  const Image mine = render_course_camera(scene, camera_named(scene, std::string(c.image) + ".exr"), 32);
  const BlockStats b = reported_block_stats(mine, read_exr(course(std::string("pathTracing/") + c.image + ".exr")).rgb, c.image);
  if (c.roulette) {
    EXPECT_NEAR(b.mean_ratio, 1.0, 0.10);
    EXPECT_LT(b.median_rel, 0.15);
  } else {
    EXPECT_LT(b.median_rel, 0.03);
    EXPECT_LT(b.p95_rel, 0.12);
  }
}
INSTANTIATE_TEST_SUITE_P(Course, PathTracingReference,
                         ::testing::Values(PtCase{"diffuse", "diffuse_next", false},
                                           PtCase{"glass", "glass_next_importance", false},
                                           PtCase{"diffuse", "diffuse_next_russian", true}),
                         [](const auto& tp) { return std::string(tp.param.image); });

// The course roulette with NEE and importance sampling at 32 spp (its limits are the 100-spp ones: the course
// roulette's block statistics are dominated by the reference's own noise).
TEST(PathTracingReference, DiffuseNextImportanceRussian) {
  REQUIRE_SHARED();
  const SceneDesc scene = load_scene(course("pathTracing/cornellbox_jaroslav_path_diffuse.xml"));
  const Image mine = render_course_camera(scene, camera_named(scene, "diffuse_next_importance_russian.exr"), 32);
  const BlockStats b = reported_block_stats(mine, read_exr(course("pathTracing/diffuse_next_importance_russian.exr")).rgb,
                                            "diffuse_next_importance_russian");
  EXPECT_NEAR(b.mean_ratio, 1.0, 0.10);
  EXPECT_LT(b.median_rel, 0.15);
}

// The other twelve pathTracing/ cameras, at kNoiseAwareSpp (a quarter of the budget above per camera), judged by the
// noise both images carry at their sample counts: the per-pixel differences mine - reference have the true image
// cancelled, so their mean divided by their own standard error (spread / sqrt n) is a paired t statistic, ~N(0, 1)
// when both estimate the same image, whatever either's noise. Over the whole image (262144 pixels) it must stay
// within 4.5 (two-sided 7e-6 per camera): a 1% gain is ~10 standard errors at 8 spp. The 32x32 blocks' statistics
// are printed for the log: the course's literal roulette and small-light NEE are heavy-tailed, and their worst
// blocks reach |z| 5-6 with no sign of bias in the image statistic; only their maximum is bounded, loosely (below).
constexpr uint32_t kNoiseAwareSpp = 8;
constexpr double kMaxImageZ = 4.5;
// Why a block limit too: a bias confined to a small object (the glass sphere losing its refraction) is diluted in
// the image statistic (|z| 4.2 with the Fresnel split's transmission dropped) while its blocks reach |z| 22. Only
// for cameras without the course roulette, whose block |z| stays Gaussian-like (clean maxima 2.2-5.0 over 256
// blocks; a roulette camera's reaches 6.2); 8 is p ~ 1e-15 per block for a normal statistic.
constexpr double kMaxBlockZ = 8.0;

struct NoiseAwareStats {
  double median_z = 0, p95_z = 0, max_z = 0, mean_z = 0;
  size_t blocks = 0;
};

// Mean and standard error of the luminance differences over pixels [x0, x1) x [y0, y1).
Estimate difference_estimate(const Image& mine, const Image& reference, int x0, int x1, int y0, int y1) {
  double sum = 0, sum2 = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const size_t i = size_t(y) * size_t(mine.width()) + size_t(x);
      const double d = double(mine.pixels()[i].luminance()) - double(reference.pixels()[i].luminance());
      sum += d;
      sum2 += d * d;
    }
  return estimate_from_sums(sum, sum2, double((x1 - x0) * (y1 - y0)));
}

double z_of(const Estimate& e) { return e.stderr_ > 0 ? std::abs(e.mean) / e.stderr_ : (e.mean == 0 ? 0 : INFINITY); }

NoiseAwareStats noise_aware_block_stats(const Image& mine, const Image& reference, int block) {
  double ref_sum = 0;
  for (const Rgb& p : reference.pixels()) ref_sum += p.luminance();
  const double ref_mean = ref_sum / double(reference.pixels().size());
  std::vector<double> z;
  for (int y = 0; y + block <= mine.height(); y += block)
    for (int x = 0; x + block <= mine.width(); x += block) {
      double r = 0;
      for (int yy = y; yy < y + block; ++yy)
        for (int xx = x; xx < x + block; ++xx) r += reference.pixels()[size_t(yy) * size_t(mine.width()) + size_t(xx)].luminance();
      if (r / double(block * block) < 1e-3 * ref_mean) continue;  // black in the reference: nothing to compare
      z.push_back(z_of(difference_estimate(mine, reference, x, x + block, y, y + block)));
    }
  NoiseAwareStats s;
  s.blocks = z.size();
  if (z.empty()) return s;
  std::sort(z.begin(), z.end());
  s.median_z = z[z.size() / 2];
  s.p95_z = z[std::min(z.size() - 1, size_t(0.95 * double(z.size())))];
  s.max_z = z.back();
  s.mean_z = z_of(difference_estimate(mine, reference, 0, mine.width(), 0, mine.height()));
  return s;
}

class PathTracingNoiseAware : public ::testing::TestWithParam<PtCase> {};
TEST_P(PathTracingNoiseAware, MatchesCourseExrWithinTheNoise) {
  REQUIRE_SHARED();
  const PtCase& c = GetParam();
  const SceneDesc scene = load_scene(course(std::string("pathTracing/cornellbox_jaroslav_path_") + c.scene + ".xml"));
  const CameraDesc& cd = scene.cameras.at(camera_named(scene, std::string(c.image) + ".exr"));
  const auto world = build_scene_world(scene);
  const Image mine = render_image(*world, cd, scene_settings(cd, scene, world->features), kNoiseAwareSpp);
  const Image ref = read_exr(course(std::string("pathTracing/") + c.image + ".exr")).rgb;
  const NoiseAwareStats s = noise_aware_block_stats(mine, ref, 32);
  reported_block_stats(mine, ref, c.image);
  std::printf("[ z   ] %s at %u spp: %zu blocks, |z| median %.2f, p95 %.2f, max %.2f; image |z| %.2f\n", c.image,
              kNoiseAwareSpp, s.blocks, s.median_z, s.p95_z, s.max_z, s.mean_z);
  ASSERT_GT(s.blocks, 100u);
  EXPECT_LT(s.mean_z, kMaxImageZ);
  if (!c.roulette) {
    EXPECT_LT(s.max_z, kMaxBlockZ) << "a block differs from the reference far beyond its noise";
  }
}
INSTANTIATE_TEST_SUITE_P(Course, PathTracingNoiseAware,
                         ::testing::Values(PtCase{"diffuse", "diffuse", false},
                                           PtCase{"glass", "glass", false},
                                           PtCase{"glass", "glass_importance_russian", true},
                                           PtCase{"diffuse", "diffuse_importance", false},
                                           PtCase{"diffuse", "diffuse_russian", true},
                                           PtCase{"diffuse", "diffuse_importance_russian", true},
                                           PtCase{"diffuse", "diffuse_next_importance", false},
                                           PtCase{"glass", "glass_importance", false},
                                           PtCase{"glass", "glass_russian", true},
                                           PtCase{"glass", "glass_next", false},
                                           PtCase{"glass", "glass_next_russian", true},
                                           PtCase{"glass", "glass_next_importance_russian", true}),
                         [](const auto& tp) { return std::string(tp.param.image); });

// Issue 19: Veach's "Ajar door" (image and checkerboard textures, instances, glass, an area light behind a door gap)
// against the course's 10 000-spp reference, at a quarter of its resolution: each 320x180 pixel is compared with the
// mean of its 4x4 block of the reference, so 8x8-pixel blocks here are the 32x32-pixel blocks. The scene's
// own rules (the course path tracer, NEE + importance sampling). The reference has one overflowed (inf) half pixel;
// reference pixels that are not finite are left out of their block's mean.
Image box_downsample(const Image& full, int factor) {
  Image out(full.width() / factor, full.height() / factor);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      Rgb sum(0.0f);
      int n = 0;
      for (int dy = 0; dy < factor; ++dy)
        for (int dx = 0; dx < factor; ++dx) {
          const Rgb c = full.at(x * factor + dx, y * factor + dy);
          if (!c.is_finite()) continue;
          sum += c;
          ++n;
        }
      out.at(x, y) = n ? sum / float(n) : Rgb(0.0f);
    }
  return out;
}

// Measured at 320x180 (block median / p95): 64 spp 0.114 / 0.447, 256 spp 0.063 / 0.242, 1536 spp 0.0302 / 0.105,
// 2048 spp 0.0266 / 0.094 — falling about like noise, so the limits need about 1600 spp (README,
// "Textures"). That costs ~17 CPU-minutes at 2048 spp, so the test runs only when KILN_VEACH_SPP names the spp.
inline constexpr int kVeachDownsample = 4;
uint32_t veach_spp() {
  const char* v = std::getenv("KILN_VEACH_SPP");
  return v ? uint32_t(std::strtoul(v, nullptr, 10)) : 0;
}
class VeachAjarReference : public ::testing::Test {};
TEST_F(VeachAjarReference, BlockLuminanceMatchesCourseExr) {
  REQUIRE_SHARED();
  const uint32_t spp = veach_spp();
  if (spp == 0) GTEST_SKIP() << "set KILN_VEACH_SPP (2048) to render veach-ajar against its reference";
  SceneDesc scene = load_scene(course("veach-ajar/scene.xml"));
  ASSERT_TRUE(scene.unsupported.empty());
  const Image ref = box_downsample(read_exr(course("veach-ajar/VeachAjar.exr")).rgb, kVeachDownsample);
  scene.cameras[0].width = ref.width();
  scene.cameras[0].height = ref.height();
  const Image mine = render_course_camera(scene, 0, spp);
  const BlockStats b = block_luminance_stats(mine, ref, 32 / kVeachDownsample);
  const ErrorStats e = error_stats(mine, ref);
  EXPECT_EQ(b.left_out.image, 0u) << "pixels that are not finite";
  std::printf("veach-ajar %dx%d at %u spp: block median %.4f p95 %.4f mean ratio %.4f mse %.4g\n", ref.width(),
              ref.height(), spp, b.median_rel, b.p95_rel, b.mean_ratio, e.mse);
  EXPECT_LT(b.median_rel, 0.03);
  EXPECT_LT(b.p95_rel, 0.12);
}

}  // namespace
}  // namespace kiln::test
