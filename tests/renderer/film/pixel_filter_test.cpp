// Pixel filters by filter importance sampling: each filter's samples follow its absolute profile (chi-square), its
// weights make the pixel estimate unbiased (weighted moments against quadrature), negative lobes carry negative
// weights, and renders with a filter stay bit-identical across thread counts, tile orders and sample ranges.
// The reference profiles below are written independently of renderer/film/pixel_filter.cpp, from their definitions.
#include "renderer/film/pixel_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/rng.h"
#include "renderer/render_util.h"
#include "support/chi2.h"

namespace kiln::test {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr uint64_t kSamples = 1'000'000;
constexpr int kGrid = 20;        // chi-square cells per axis: not a divisor of the filter table's 256 bins
constexpr int kQuadrature = 4000;  // midpoint points per cell and axis for the expected probabilities

struct FilterCase {
  const char* text;  // as given to --filter; for a filter given by its parameters, a label
  const char* name;
  double width;      // full width in pixels
  double sigma = 0;  // Gaussian standard deviation; 0: width / 6, as --filter sets it
  double b = 1.0 / 3.0, c = 1.0 / 3.0;  // Mitchell-Netravali B, C
  bool parameters = false;  // built from width, sigma, B and C as a scene's filter is (pbrt's PixelFilter), not parsed
};

const FilterCase kCases[] = {{"box", "box", 1.0},
                             {"box:2.5", "box", 2.5},
                             {"triangle", "triangle", 2.0},
                             {"triangle:1.3", "triangle", 1.3},
                             {"gaussian", "gaussian", 3.0},
                             {"gaussian:1.5", "gaussian", 1.5},
                             {"gaussian:0.01", "gaussian", 0.01},
                             {"blackman-harris", "blackman-harris", 1.5},
                             {"blackman-harris:4", "blackman-harris", 4.0},
                             {"mitchell", "mitchell", 4.0},
                             {"mitchell:2", "mitchell", 2.0},
                             // Parameters the --filter form cannot give: a sigma other than width / 6, B != C (a
                             // swap of B and C or an ignored sigma changes these profiles).
                             {"scene gaussian r1.5 sigma0.3", "gaussian", 3.0, 0.3, 0, 0, true},
                             {"scene gaussian r2 sigma0.9", "gaussian", 4.0, 0.9, 0, 0, true},
                             {"scene mitchell B0.5 C0.25", "mitchell", 4.0, 0, 0.5, 0.25, true},
                             {"scene mitchell B0 C0.5", "mitchell", 3.0, 0, 0.0, 0.5, true}};

PixelFilterDesc desc_of(const FilterCase& c) {
  if (!c.parameters) return parse_pixel_filter(c.text);
  PixelFilterDesc d;
  d.kind = std::string(c.name) == "gaussian" ? PixelFilterKind::Gaussian : PixelFilterKind::Mitchell;
  d.radius = float(0.5 * c.width);
  d.sigma = float(c.sigma);
  d.b = float(c.b);
  d.c = float(c.c);
  return d;
}

// Mitchell-Netravali cubic on t in [-2, 2] (Mitchell & Netravali 1988, eq. 8).
double mitchell(double t, double B, double C) {
  t = std::abs(t);
  if (t < 1.0) return ((12 - 9 * B - 6 * C) * t * t * t + (-18 + 12 * B + 6 * C) * t * t + (6 - 2 * B)) / 6.0;
  if (t < 2.0) return ((-B - 6 * C) * t * t * t + (6 * B + 30 * C) * t * t + (-12 * B - 48 * C) * t + (8 * B + 24 * C)) / 6.0;
  return 0.0;
}

// The 1D profile g of a case (f(x, y) = g(x) g(y)), from the filters' definitions.
double reference_g(const FilterCase& c, double x) {
  const double w = c.width, r = 0.5 * w;
  if (std::abs(x) > r) return 0.0;
  const std::string n = c.name;
  if (n == "box") return 1.0;
  if (n == "triangle") return r - std::abs(x);
  if (n == "gaussian") {  // minus the value at the radius (pbrt-v4's GaussianFilter)
    const double s = c.sigma > 0 ? c.sigma : w / 6.0;
    return std::exp(-x * x / (2 * s * s)) - std::exp(-r * r / (2 * s * s));
  }
  if (n == "blackman-harris") {  // Cycles' filter_func_blackman_harris(width, x)
    const double t = 2.0 * kPiD * (x / w + 0.5);
    return 0.35875 - 0.48829 * std::cos(t) + 0.14128 * std::cos(2 * t) - 0.01168 * std::cos(3 * t);
  }
  return mitchell(4.0 * x / w, c.b, c.c);  // pbrt-v4: Mitchell1D(2 x / radius)
}

// ∫ over [a, b] of h(g(x), x), midpoint rule.
template <class H>
double integrate(const FilterCase& c, double a, double b, H&& h, int n = kQuadrature) {
  const double dx = (b - a) / n;
  double s = 0;
  for (int i = 0; i < n; ++i) {
    const double x = a + (i + 0.5) * dx;
    s += h(reference_g(c, x), x);
  }
  return s * dx;
}

class Filters : public ::testing::TestWithParam<FilterCase> {};

// Why: filter importance sampling draws film positions with density |f| / ∫|f|; a wrong inverse CDF, table or
// radius shows as a chi-square misfit.
TEST_P(Filters, SamplesFollowTheAbsoluteProfile) {
  const FilterCase& c = GetParam();
  const PixelFilter filter(desc_of(c));
  const double r = 0.5 * c.width, cell = 2.0 * r / kGrid;
  std::vector<double> px(kGrid);
  double total = 0;
  for (int i = 0; i < kGrid; ++i) {
    px[size_t(i)] = integrate(c, -r + i * cell, -r + (i + 1) * cell, [](double g, double) { return std::abs(g); });
    total += px[size_t(i)];
  }
  for (double& p : px) p /= total;
  std::vector<double> expected(size_t(kGrid * kGrid));
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) expected[size_t(j * kGrid + i)] = px[size_t(i)] * px[size_t(j)];
  std::vector<uint64_t> observed(expected.size(), 0);
  Rng rng(17, 3);
  for (uint64_t k = 0; k < kSamples; ++k) {
    const FilterSample s = filter.sample(rng.next_2d());
    const int i = int(std::floor((s.offset.x + r) / cell)), j = int(std::floor((s.offset.y + r) / cell));
    ASSERT_TRUE(std::abs(s.offset.x) <= r && std::abs(s.offset.y) <= r)
        << c.text << ": sample (" << s.offset.x << ", " << s.offset.y << ") outside the radius " << r;
    ++observed[size_t(std::clamp(j, 0, kGrid - 1) * kGrid + std::clamp(i, 0, kGrid - 1))];
  }
  const auto result = chi2_discrete(observed, expected, 0.01, int(std::size(kCases)));
  EXPECT_TRUE(result.passed) << c.text << ": " << result.message;
}

// Why: the weight f / (pdf ∫f) makes the mean of weight * h(offset) an unbiased estimate of ∫ f h / ∫ f for any
// h. Checked for smooth test functions against quadrature of the reference profile, within 4.5 standard errors.
TEST_P(Filters, WeightsMakeThePixelEstimateUnbiased) {
  const FilterCase& c = GetParam();
  const PixelFilter filter(desc_of(c));
  const double r = 0.5 * c.width;
  struct Moment {
    const char* name;
    double (*h)(double, double, double);  // h(x, y, r)
  };
  const Moment moments[] = {{"1", [](double, double, double) { return 1.0; }},
                            {"x^2", [](double x, double, double rr) { return x * x / (rr * rr); }},
                            {"x^2 y^2", [](double x, double y, double rr) { return x * x * y * y / (rr * rr * rr * rr); }},
                            {"(x + 0.3 r)^3 + y", [](double x, double y, double rr) {
                               return std::pow(x / rr + 0.3, 3) + y / rr;
                             }}};
  const double g_int = integrate(c, -r, r, [](double g, double) { return g; }, 200000);
  const auto g_moment = [&](int power) {
    return integrate(c, -r, r, [&](double g, double x) { return g * std::pow(x / r, power); }, 200000) / g_int;
  };
  // Exact values, from the separable moments of g / ∫g: E[x^k] under the normalised filter.
  const double m1 = g_moment(1), m2 = g_moment(2), m3 = g_moment(3);
  const double exact[] = {1.0, m2, m2 * m2, m3 + 0.9 * m2 + 0.27 * m1 + 0.027 + m1};
  Rng rng(5, 9);
  double sum[4] = {}, sum2[4] = {};
  for (uint64_t k = 0; k < kSamples; ++k) {
    const FilterSample s = filter.sample(rng.next_2d());
    ASSERT_TRUE(std::isfinite(s.weight)) << c.text;
    for (int m = 0; m < 4; ++m) {
      const double v = double(s.weight) * moments[m].h(s.offset.x, s.offset.y, r);
      sum[m] += v;
      sum2[m] += v * v;
    }
  }
  for (int m = 0; m < 4; ++m) {
    const Estimate e = estimate_from_sums(sum[m], sum2[m], double(kSamples));
    // Box and triangle weights are exactly 1 (the "1" moment then has no spread at all).
    const double tol = std::max(4.5 * e.stderr_, 1e-6);
    EXPECT_NEAR(e.mean, exact[m], tol) << c.text << ": E[w h] for h = " << moments[m].name;
  }
}

// Why: a sample in a negative lobe must subtract. The weight's sign is the profile's sign at the sample.
TEST_P(Filters, WeightSignFollowsTheProfile) {
  const FilterCase& c = GetParam();
  const PixelFilter filter(desc_of(c));
  Rng rng(23, 1);
  int negative = 0;
  for (int k = 0; k < 200000; ++k) {
    const FilterSample s = filter.sample(rng.next_2d());
    const double f = reference_g(c, s.offset.x) * reference_g(c, s.offset.y);
    if (std::abs(f) < 1e-6) continue;  // at a zero crossing the sign is a matter of rounding
    ASSERT_EQ(s.weight < 0, f < 0) << c.text << " at (" << s.offset.x << ", " << s.offset.y << "): f " << f
                                   << ", weight " << s.weight;
    negative += s.weight < 0;
  }
  if (std::string(c.name) == "mitchell") EXPECT_GT(negative, 0) << "Mitchell's negative lobes were never sampled";
  else EXPECT_EQ(negative, 0);
}

// Why: the film must hold the filter's weighted estimate, not only samples placed by the filter. The image of a
// sharp edge (the background, 1, left of the image's centre line; a black quad right of it) is, in the column whose
// centre lies d pixels from the edge, the filter's step response: the share of ∫g over offsets x < -d. Mitchell's
// negative lobes overshoot it (above 1 on the bright side, below 0 on the dark side); samples placed by |g| but not
// weighted give the share of ∫|g| instead, 0.02-0.06 off next to the edge. Column means over 8 rows x 2048 spp
// have standard errors of ~0.004.
TEST_P(Filters, RenderedEdgeIsTheStepResponse) {
  const FilterCase& c = GetParam();
  constexpr int kSize = 8;
  constexpr uint32_t kSpp = 2048;
  SceneDesc scene = lambertian_scene(0.0f);
  scene.background = Rgb(1.0f);
  MeshDesc quad;
  quad.name = "right half";
  quad.positions = {{0, -100, -2}, {100, -100, -2}, {100, 100, -2}, {0, 100, -2}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 0;
  scene.meshes.push_back(quad);
  CameraDesc cam;
  cam.id = "1";
  cam.gaze = {0, 0, -1};
  cam.up = {0, 1, 0};
  cam.use_fov = true;
  cam.fov_y_deg = 30;
  cam.width = cam.height = kSize;
  scene.cameras.push_back(cam);
  const auto world = build_world(scene, {});
  const Camera camera(cam);
  Film film(kSize, kSize);
  RenderOptions ro;
  ro.seed = 29;
  ro.spp_total = kSpp;
  ro.filter = desc_of(c);
  render_samples(*world, camera, scene_settings(cam, scene, world->features), ro, 0, kSpp, film);

  const double r = 0.5 * c.width;
  const double g_int = integrate(c, -r, r, [](double g, double) { return g; }, 200000);
  for (int x = 0; x < kSize; ++x) {
    double sum = 0, sum2 = 0, n = 0;
    for (int y = 0; y < kSize; ++y) {
      const PixelSum& p = film.at(x, y);
      sum += p.r;
      sum2 += p.lum2;  // grey samples: luminance = value
      n += p.n;
    }
    const Estimate e = estimate_from_sums(sum, sum2, n);
    const double d = x + 0.5 - 0.5 * kSize;  // column centre to edge, in pixels
    const double expected =
        -d <= -r ? 0.0 : integrate(c, -r, std::min(-d, r), [](double g, double) { return g; }, 200000) / g_int;
    EXPECT_NEAR(e.mean, expected, std::max(4.5 * e.stderr_, 1e-5)) << c.text << ": column " << x << " (d = " << d << ")";
  }
}

INSTANTIATE_TEST_SUITE_P(PixelFilter, Filters, ::testing::ValuesIn(kCases), [](const auto& p) {
  std::string n = p.param.text;
  for (char& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
});

// Why: the default 1-px box must reproduce the unfiltered renders bit for bit (film position = sampler value).
TEST(PixelFilter, OnePixelBoxIsTheSamplerValueItself) {
  const PixelFilter box{PixelFilterDesc{}};
  Rng rng(3, 3);
  for (int k = 0; k < 100000; ++k) {
    const Vec2f u = rng.next_2d();
    const FilterSample s = box.sample(u);
    ASSERT_EQ(0.5f + s.offset.x, u.x);
    ASSERT_EQ(0.5f + s.offset.y, u.y);
    ASSERT_EQ(s.weight, 1.0f);
  }
}

// Why: `--filter gaussian:0.01` is how a race matches Cycles' pixel-centre sampling.
TEST(PixelFilter, NarrowGaussianSamplesPixelCentres) {
  const PixelFilter g(parse_pixel_filter("gaussian:0.01"));
  Rng rng(4, 4);
  for (int k = 0; k < 100000; ++k) {
    const FilterSample s = g.sample(rng.next_2d());
    ASSERT_LE(std::abs(s.offset.x), 0.005f);
    ASSERT_LE(std::abs(s.offset.y), 0.005f);
  }
}

TEST(PixelFilter, ParsesNamesAndWidths) {
  EXPECT_EQ(parse_pixel_filter("box").radius, 0.5f);
  EXPECT_EQ(parse_pixel_filter("blackman-harris").radius, 0.75f);
  EXPECT_EQ(parse_pixel_filter("blackman-harris").kind, PixelFilterKind::BlackmanHarris);
  EXPECT_EQ(parse_pixel_filter("gaussian:0.01").radius, 0.005f);
  EXPECT_FLOAT_EQ(parse_pixel_filter("gaussian:3").sigma, 0.5f);
  EXPECT_EQ(parse_pixel_filter("mitchell").radius, 2.0f);
  EXPECT_EQ(describe_pixel_filter(parse_pixel_filter("triangle:1.25")), "triangle:1.25");
  for (const char* bad : {"lanczos", "", "box:", "box:0", "box:-1", "box:abc", "box:1x", "gaussian:100", "Box",
                          "mitchell:nan", "triangle:inf"}) {
    try {
      (void)parse_pixel_filter(bad);
      ADD_FAILURE() << "'" << bad << "' accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--filter"), std::string::npos) << e.what();
    }
  }
}

// Why: the filter comes from --filter, else from the scene's camera (pbrt's PixelFilter), else box 1 px.
TEST(PixelFilter, CommandLineOverridesTheSceneWhichOverridesTheDefault) {
  CameraDesc cam;
  EXPECT_EQ(pixel_filter_for(cam, std::nullopt).kind, PixelFilterKind::Box);
  EXPECT_EQ(pixel_filter_for(cam, std::nullopt).radius, 0.5f);
  PixelFilterDesc scene_filter;
  scene_filter.kind = PixelFilterKind::Gaussian;
  scene_filter.radius = 1.5f;
  cam.filter = scene_filter;
  EXPECT_EQ(pixel_filter_for(cam, std::nullopt).kind, PixelFilterKind::Gaussian);
  EXPECT_EQ(pixel_filter_for(cam, std::string("mitchell")).kind, PixelFilterKind::Mitchell);
}

bool bit_identical(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Rgb)) == 0;
}

Image render_filtered(const World& w, const CameraDesc& cd, const IntegratorSettings& s, const char* filter,
                      int threads, bool reverse, std::vector<std::pair<uint32_t, uint32_t>> ranges) {
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const Camera cam(cd);
  Film film(cam.width(), cam.height());
  RenderOptions ro;
  ro.seed = 11;
  ro.spp_total = 8;
  ro.reverse_tile_order = reverse;
  ro.filter = parse_pixel_filter(filter);
  for (const auto& [first, last] : ranges) render_samples(w, cam, s, ro, first, last, film);
  return film.mean();
}

// Why: negative-weight samples (Mitchell) and table lookups must not break determinism or sample-range merging.
TEST(PixelFilter, FilteredRendersAreBitIdenticalAcrossThreadsTilesAndRanges) {
  SceneDesc scene = load_scene(std::string(KILN_SOURCE_DIR) + "/scenes/default.xml");
  scene.cameras[0].width = scene.cameras[0].height = 32;
  const auto world = build_world(scene, {});
  const IntegratorSettings s = scene_settings(scene.cameras[0], scene, world->features);
  for (const char* f : {"mitchell", "blackman-harris"}) {
    const Image one = render_filtered(*world, scene.cameras[0], s, f, 1, false, {{0, 8}});
    EXPECT_TRUE(bit_identical(one, render_filtered(*world, scene.cameras[0], s, f, 2, true, {{0, 8}}))) << f;
    EXPECT_TRUE(bit_identical(one, render_filtered(*world, scene.cameras[0], s, f, 2, false, {{0, 3}, {3, 8}}))) << f;
    // And the filter matters (the comparison can fail).
    EXPECT_FALSE(bit_identical(one, render_filtered(*world, scene.cameras[0], s, "box", 2, false, {{0, 8}}))) << f;
  }
}

}  // namespace
}  // namespace kiln::test
