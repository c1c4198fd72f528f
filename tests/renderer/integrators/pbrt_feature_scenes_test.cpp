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

#include "renderer/analysis/image_compare.h"
#include "renderer/film/pixel_filter.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render_util.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

constexpr int kBlock = 16;
constexpr double kMedianLimit = 0.02;
constexpr double kP95Limit = 0.08;
constexpr double kMeanRatioLimit = 0.02;

std::string features(const std::string& rel) { return shared_dir() + "/scenes/pbrt/features/" + rel; }

BlockStats render_against_reference(const std::string& name, uint32_t spp, uint64_t seed) {
  const SceneDesc scene = load_scene(features(name + ".pbrt"));
  const auto world = build_scene_world(scene);
  const CameraDesc& cd = scene.cameras.at(0);
  const Camera cam(cd);
  Film film(cam.width(), cam.height());
  RenderOptions ro;
  ro.seed = seed;
  ro.spp_total = spp;
  ro.filter = pixel_filter_for(cd, std::nullopt);
  render_samples(*world, cam, scene_settings(cd, scene, world->features), ro, 0, spp, film);
  const Image reference = read_exr(features("reference/" + name + ".exr")).rgb;
  const BlockStats st = block_luminance_stats(film.mean(), reference, kBlock);
  std::cout << name << " vs pbrt-v4, " << spp << " spp, " << kBlock << "-px blocks: median " << st.median_rel
            << ", p95 " << st.p95_rel << ", mean ratio " << st.mean_ratio << " over " << st.blocks << " blocks\n";
  return st;
}

TEST(PbrtFeatureScenes, EnvEquiareaMatchesPbrtV4) {
  KILN_NEED_SHARED_PATH(features("env-equiarea.pbrt"));
  const BlockStats st = render_against_reference("env-equiarea", 16, 3);
  EXPECT_EQ(st.left_out.image, 0u) << "pixels that are not finite";
  EXPECT_LT(st.median_rel, kMedianLimit);
  EXPECT_LT(st.p95_rel, kP95Limit);
  EXPECT_NEAR(st.mean_ratio, 1.0, kMeanRatioLimit);
}

}  // namespace
}  // namespace kiln::test
