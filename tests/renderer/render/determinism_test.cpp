// Same seed => bit-identical pixels for any thread count, tile order and spp split: every pixel sample draws from
// its own RNG stream keyed by (seed, pixel, sample index) and each pixel is summed by one thread in sample order.
#include <gtest/gtest.h>

#include <cstring>

#include "renderer/render_util.h"

namespace kiln::test {
namespace {

bool bit_identical(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Rgb)) == 0;
}

TEST(Determinism, ThreadCountAndTileOrderDoNotChangePixels) {
  for (const RuleCase& rc : default_scene_rule_cases(40)) {
    SCOPED_TRACE(rc.name);
    const SceneDesc& scene = rc.scene;
    const auto world = build_world(scene, {});
    const IntegratorSettings s = scene_settings(scene.cameras[0], scene, world->features);
    const Image one = render_image(*world, scene.cameras[0], s, 8, 42, 1);
    const Image two = render_image(*world, scene.cameras[0], s, 8, 42, 2);
    const Image reversed = render_image(*world, scene.cameras[0], s, 8, 42, 2, true);
    EXPECT_TRUE(bit_identical(one, two));
    EXPECT_TRUE(bit_identical(one, reversed));
    // And the seed matters (the comparison can fail).
    const Image other_seed = render_image(*world, scene.cameras[0], s, 8, 43, 2);
    EXPECT_FALSE(bit_identical(one, other_seed));
  }
}

TEST(Determinism, SampleRangesMergeToTheFullRender) {
  for (const RuleCase& rc : default_scene_rule_cases(40)) {
    SCOPED_TRACE(rc.name);
    const SceneDesc& scene = rc.scene;
    const auto world = build_world(scene, {});
    const IntegratorSettings s = scene_settings(scene.cameras[0], scene, world->features);
    const Camera cam(scene.cameras[0]);
    RenderOptions ro;
    ro.seed = 5;
    ro.spp_total = 8;
    Film full(cam.width(), cam.height()), waves(cam.width(), cam.height());
    render_samples(*world, cam, s, ro, 0, 8, full);
    render_samples(*world, cam, s, ro, 0, 1, waves);
    render_samples(*world, cam, s, ro, 1, 2, waves);
    render_samples(*world, cam, s, ro, 2, 4, waves);
    render_samples(*world, cam, s, ro, 4, 8, waves);
    EXPECT_TRUE(bit_identical(full.mean(), waves.mean()));
  }
}

}  // namespace
}  // namespace kiln::test

namespace kiln::test {
namespace {

// The integrator specialised on the scene's feature mask must give exactly the image of the general one.
TEST(Determinism, FeatureMaskSpecialisationDoesNotChangePixels) {
  SceneDesc scene = furnace_box(0.6f, Rgb(1.0f));
  scene.cameras[0].width = scene.cameras[0].height = 16;
  const auto world = build_world(scene, {});
  ASSERT_FALSE(world->features & kFeatureDelta);
  ASSERT_FALSE(world->features & (kFeatureSpheres | kFeatureInstances));  // the meshes-only kernel
  IntegratorSettings s = PathSettings{};
  s.features = world->features;
  const Image specialised = render_image(*world, scene.cameras[0], s, 4, 3);
  s.features = kFeatureAll;
  const Image general = render_image(*world, scene.cameras[0], s, 4, 3);
  EXPECT_TRUE(bit_identical(specialised, general));
}

}  // namespace
}  // namespace kiln::test

namespace kiln::test {
namespace {

// Handing the meshes' arrays to the world (kiln render / kiln profile) must not change a pixel, and must really
// empty the description (else the memory saving is not there).
TEST(Determinism, WorldTakingTheMeshesRendersTheSameImage) {
  for (const char* file : {"/scenes/default.xml", "/scenes/killeroo_blinnphong.xml"}) {
    SCOPED_TRACE(file);
    SceneDesc scene = load_scene(std::string(KILN_SOURCE_DIR) + file);
    scene.cameras[0].width = scene.cameras[0].height = 24;
    const auto copied = build_world(scene, {});
    const auto taken = build_world_taking_meshes(scene, {});
    size_t left = 0;
    for (const MeshDesc& m : scene.meshes)
      if (!m.is_instance_base) left += m.positions.size() + m.indices.size() + m.normals.size() + m.uvs.size();
    EXPECT_EQ(left, 0u);
    EXPECT_EQ(copied->stats.triangles, taken->stats.triangles);
    const IntegratorSettings s = scene_settings(scene.cameras[0], scene, copied->features);
    EXPECT_TRUE(bit_identical(render_image(*copied, scene.cameras[0], s, 2, 9), render_image(*taken, scene.cameras[0], s, 2, 9)));
  }
}

}  // namespace
}  // namespace kiln::test
