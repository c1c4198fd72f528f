// Kiln against pbrt-v4 on ../shared/scenes/pbrt/features/media.pbrt (a homogeneous chromatic fog sphere, g 0.4, and
// a 4^3 uniform-grid smoke block, g -0.2, under a spot light and a quad light; volpath maxdepth 20) and pbrt-v4's
// 256-spp render of it (reference/media.exr). Kiln renders it as `kiln render` does at 64 spp and is held to the
// issue's limits over 16-px blocks (luminance median < 2%, p95 < 8%, mean within 2%), over the image and over crops
// of the two media.
//
// One region is left out of the image statistics, because neither renderer defines it: the smoke box's bottom face
// lies in the floor's plane (z = 0), and where a ray meets both at the same distance, floating-point rounding
// decides which comes first. Meeting the box's face first, the ray crosses it into the vacuum below, passes under
// the floor and sees nothing; meeting the floor first, it sees the floor lit by the spot light. pbrt-v4 mixes the
// two within each pixel (its 2x2 footprint reads ~55% of the lit floor's luminance), Kiln (Embree) in bands of rows:
// there the blocks differ by 18-50%. Lowering the box by 0.001 makes Kiln's footprint the lit floor everywhere
// (Kiln: 0.15-0.18, pbrt: 0.09). The indirect light from that footprint raises the dark wall above it in Kiln by
// ~5% (inside the limits). Measured at 64 spp, seeds 1 and 2, with the footprint left out: median 0.74% / 0.68%,
// p95 6.7% / 7.0%, mean 1.0011 / 1.0010; at 256 spp p95 6.3%. Two Kiln renders at 64 spp differ by a p95 of
// 4.5% (noise), pbrt's reference adds its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "renderer/analysis/image_compare.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render_util.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

constexpr uint32_t kSpp = 64;
constexpr int kBlock = 16;
constexpr double kMedianLimit = 0.02, kP95Limit = 0.08, kMeanLimit = 0.02;

// Block rectangles [x0, x1) x [y0, y1) in 16-px blocks of the 480x320 image.
struct BlockRect {
  int x0, x1, y0, y1;
  bool contains(int bx, int by) const { return bx >= x0 && bx < x1 && by >= y0 && by < y1; }
};
constexpr BlockRect kFloorUnderBox{6, 14, 11, 15};  // the smoke box's footprint on the floor (see above)
constexpr BlockRect kFog{16, 24, 6, 14};            // the fog sphere
constexpr BlockRect kSmoke{11, 15, 9, 12};          // the smoke block above its footprint
constexpr BlockRect kWhole{0, 30, 0, 20};

struct Stats {
  double median = 0, p95 = 0, mean_ratio[3] = {0, 0, 0}, luminance_ratio = 0;
  size_t blocks = 0;
};

Rgb block_mean(const Image& img, int bx, int by) {
  Rgb s(0.0f);
  for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
    for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) s += img.at(x, y);
  return s / float(kBlock * kBlock);
}

// Relative block luminance errors over the blocks of `area` outside `left_out`.
Stats compare(const Image& a, const Image& ref, const BlockRect& area, const BlockRect* left_out = nullptr) {
  std::vector<double> rel;
  double sum_a[3] = {0, 0, 0}, sum_r[3] = {0, 0, 0}, lum_a = 0, lum_r = 0;
  for (int by = area.y0; by < area.y1; ++by)
    for (int bx = area.x0; bx < area.x1; ++bx) {
      if (left_out && left_out->contains(bx, by)) continue;
      const Rgb ma = block_mean(a, bx, by), mr = block_mean(ref, bx, by);
      rel.push_back(std::abs(double(ma.luminance()) - mr.luminance()) / mr.luminance());
      lum_a += ma.luminance();
      lum_r += mr.luminance();
      for (int c = 0; c < 3; ++c) sum_a[c] += ma[c], sum_r[c] += mr[c];
    }
  std::sort(rel.begin(), rel.end());
  Stats s;
  s.blocks = rel.size();
  s.median = rel[rel.size() / 2];
  s.p95 = rel[size_t(0.95 * double(rel.size() - 1))];
  s.luminance_ratio = lum_a / lum_r;
  for (int c = 0; c < 3; ++c) s.mean_ratio[c] = sum_a[c] / sum_r[c];
  return s;
}

void expect_within_limits(const Stats& s, const std::string& what, bool per_channel) {
  std::cout << "media.pbrt vs pbrt-v4, " << what << ", " << kSpp << " spp: median " << s.median << ", p95 " << s.p95
            << ", mean ratio " << s.luminance_ratio << " (RGB " << s.mean_ratio[0] << " " << s.mean_ratio[1] << " "
            << s.mean_ratio[2] << ") over " << s.blocks << " blocks\n";
  EXPECT_LT(s.median, kMedianLimit) << what;
  EXPECT_LT(s.p95, kP95Limit) << what;
  EXPECT_NEAR(s.luminance_ratio, 1.0, kMeanLimit) << what;
  if (!per_channel) return;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.mean_ratio[c], 1.0, kMeanLimit) << what << ", channel " << c;
}

TEST(PbrtReference, MediaSceneMatchesPbrtV4) {
  const std::string dir = shared_dir() + "/scenes/pbrt/features/";
  KILN_NEED_SHARED_PATH(dir + "media.pbrt");
  const SceneDesc scene = load_scene(dir + "media.pbrt");
  const auto world = build_scene_world(scene);
  ASSERT_EQ(world->media.size(), 2u);
  const IntegratorSettings settings = scene_settings(scene.cameras.at(0), scene, world->features);
  ASSERT_TRUE(std::holds_alternative<VolPathSettings>(settings.method)) << settings.describe();
  RenderStats rs;
  const Image image = render_like_kiln(scene, *world, kSpp, 1, &rs);
  EXPECT_EQ(rs.rays.nan_samples, 0u);
  const Image reference = read_exr(dir + "reference/media.exr").rgb;
  ASSERT_EQ(image.width(), kWhole.x1 * kBlock);
  ASSERT_EQ(image.height(), kWhole.y1 * kBlock);
  EXPECT_EQ(block_luminance_stats(image, reference, kBlock).left_out.image, 0u) << "pixels that are not finite";
  expect_within_limits(compare(image, reference, kWhole, &kFloorUnderBox), "image without the box's footprint", false);
  expect_within_limits(compare(image, reference, kFog), "fog sphere", true);
  expect_within_limits(compare(image, reference, kSmoke), "smoke block", true);
}

}  // namespace
}  // namespace kiln::test
