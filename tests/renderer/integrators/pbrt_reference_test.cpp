// Kiln against pbrt-v4 on the same file: killeroo-simple.pbrt and pbrt-v4's own render of it
// (../shared/scenes/pbrt/killeroos/reference/: 700x700, 256 spp, halton, volpath maxdepth 5, Gaussian filter).
// Kiln renders the file as `kiln render` does (its Gaussian PixelFilter default, Kiln's rules) at 64 spp and is held
// to the limits over 16-px blocks: luminance median < 2%, p95 < 8%.
//
// What remains between the two images is measured, not tuned away (README, pbrt-v4 differences): Kiln is darker by
// 10-24% in the dimmest blocks, the killeroos' crevices lit by interreflection, and ~0.8% in the mean over the
// killeroos. Two Kiln seeds differ there by a block p95 of 4.5%, and doubling the samples leaves the difference as it
// is, so it is systematic: pbrt multiplies spectra along a path where Kiln multiplies RGB triples (for the saturated
// base colour 0.4/0.2/0.2 the spectral product of two bounces is larger), and pbrt-v4's layered exit weight
// (LayeredExitWeight::PbrtV4, which Kiln does not use by default) adds 0.6% on the killeroos.
#include <gtest/gtest.h>

#include "renderer/pbrt_reference_util.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

constexpr uint32_t kSpp = 64;
constexpr double kMedianLimit = 0.02;
constexpr double kP95Limit = 0.08;

std::string killeroos(const std::string& rel) { return shared_dir() + "/scenes/pbrt/killeroos/" + rel; }

TEST(PbrtReference, KillerooSimpleMatchesPbrtV4) {
  KILN_NEED_SHARED_PATH(killeroos("killeroo-simple.pbrt"));
  ASSERT_EQ(pixel_filter_for(load_scene(killeroos("killeroo-simple.pbrt")).cameras.at(0), std::nullopt).kind,
            PixelFilterKind::Gaussian)
      << "pbrt's default PixelFilter";
  const BlockStats st = render_against_reference("killeroo-simple", killeroos("killeroo-simple.pbrt"),
                                                 killeroos("reference/killeroo-simple.exr"), kSpp, 3);
  EXPECT_EQ(st.left_out.image, 0u) << "pixels that are not finite";
  EXPECT_LT(st.median_rel, kMedianLimit);
  EXPECT_LT(st.p95_rel, kP95Limit);
  EXPECT_NEAR(st.mean_ratio, 1.0, 0.01);
}

}  // namespace
}  // namespace kiln::test
