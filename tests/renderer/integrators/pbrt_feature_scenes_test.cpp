// Kiln against pbrt-v4 on the feature scenes written for issue 27 (../shared/scenes/pbrt/features/, pbrt-v4's
// renders in reference/), held to the limits over 16-px blocks: luminance median < 2%, p95 < 8%, mean ratio
// within 2%.
//
// env-equiarea.pbrt (480x320, 256 spp in pbrt): diffuse, rough gold and glass spheres on a grey floor under an
// equal-area sky with a 3-degree sun. Kiln renders it at full resolution and 16 spp: two Kiln seeds differ by a
// block p95 of ~1.9% and a median of ~0.25% there (the sun's caustic under the glass ball and the gold ball's
// sparkle are the noisiest blocks), so the limits hold with the noise far inside them; what remains against pbrt
// is measured in the README (pbrt-v4 differences).
//
// textures-alpha.pbrt (480x360, 256 spp in pbrt): a floor whose reflectance is a mix of a scaled sRGB imagemap and a
// checkerboard, a quad cut out by a float imagemap alpha (a leaf with a slot), a sphere, a disk light and a distant
// light. Kiln renders it at 16 spp over the whole frame and over the crop that holds the cut-out leaf, its shadow and
// the textured floor around them (x 128-352, y 80-240). Two Kiln seeds differ there by a block median of ~0.3% and
// a p95 of ~2.5% (the leaf's edges and its penumbra are the noisiest blocks); against pbrt the crop measured median
// 0.2%, p95 1.2-1.8%, mean ratio 1.0001-1.0005 over three seeds, so the limits hold with the noise inside them.
#include <gtest/gtest.h>

#include "renderer/pbrt_reference_util.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

BlockStats feature_scene_against_pbrt(const std::string& name, uint32_t spp, uint64_t seed) {
  return render_against_reference(name, feature_scene(name + ".pbrt"), feature_scene("reference/" + name + ".exr"),
                                  spp, seed);
}

TEST(PbrtFeatureScenes, EnvEquiareaMatchesPbrtV4) {
  KILN_NEED_SHARED_PATH(feature_scene("env-equiarea.pbrt"));
  expect_within_feature_limits(feature_scene_against_pbrt("env-equiarea", 16, 3), "env-equiarea");
}

TEST(PbrtFeatureScenes, TexturesAlphaMatchesPbrtV4) {
  KILN_NEED_SHARED_PATH(feature_scene("textures-alpha.pbrt"));
  const Image kiln = render_like_kiln(feature_scene("textures-alpha.pbrt"), 16, 3);
  const Image pbrt = read_exr(feature_scene("reference/textures-alpha.exr")).rgb;
  expect_within_feature_limits(blocks_against_reference("textures-alpha, 16 spp", kiln, pbrt), "whole image");
  // The cut-out leaf, its shadow and the textured floor around them.
  const PixelRect leaf_and_floor{128, 80, 352, 240};
  expect_within_feature_limits(
      blocks_against_reference("textures-alpha's leaf and floor, 16 spp", kiln, pbrt, leaf_and_floor),
      "leaf and floor");
}

}  // namespace
}  // namespace kiln::test
