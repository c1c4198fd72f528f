// Kiln against pbrt-v4 on the feature scenes written for issue 27 (../shared/scenes/pbrt/features/, pbrt-v4's
// renders in reference/), held to the limits over 16-px blocks: luminance median < 2%, p95 < 8%, mean ratio
// within 2%.
//
// env-equiarea.pbrt (480x320, 256 spp in pbrt): diffuse, rough gold and glass spheres on a grey floor under an
// equal-area sky with a 3-degree sun. Kiln renders it at full resolution and 16 spp: two Kiln seeds differ by a
// block p95 of ~1.9% and a median of ~0.25% there (the sun's caustic under the glass ball and the gold ball's
// sparkle are the noisiest blocks), so the limits hold with the noise far inside them; what remains against pbrt
// is measured in the README (pbrt-v4 differences).
#include <gtest/gtest.h>

#include "renderer/pbrt_reference_util.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

constexpr double kMedianLimit = 0.02;
constexpr double kP95Limit = 0.08;
constexpr double kMeanRatioLimit = 0.02;

std::string features(const std::string& rel) { return shared_dir() + "/scenes/pbrt/features/" + rel; }

BlockStats feature_scene_against_pbrt(const std::string& name, uint32_t spp, uint64_t seed) {
  return render_against_reference(name, features(name + ".pbrt"), features("reference/" + name + ".exr"), spp, seed);
}

TEST(PbrtFeatureScenes, EnvEquiareaMatchesPbrtV4) {
  KILN_NEED_SHARED_PATH(features("env-equiarea.pbrt"));
  const BlockStats st = feature_scene_against_pbrt("env-equiarea", 16, 3);
  EXPECT_EQ(st.left_out.image, 0u) << "pixels that are not finite";
  EXPECT_LT(st.median_rel, kMedianLimit);
  EXPECT_LT(st.p95_rel, kP95Limit);
  EXPECT_NEAR(st.mean_ratio, 1.0, kMeanRatioLimit);
}

}  // namespace
}  // namespace kiln::test
