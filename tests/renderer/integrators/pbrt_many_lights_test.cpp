// A many-lights scene in pbrt-v4's format (tests/data/pbrt/many_lights.pbrt: 48 one-sided ceiling lamps whose
// radiance spans 100x in random colours, in a room with coloured walls) renders with the light hierarchy by default,
// lamps split into their triangles, and its image matches the power sampler's within noise block by block.
#include <gtest/gtest.h>

#include <cstdio>

#include "renderer/render_util.h"

namespace kiln::test {
namespace {

constexpr int kBlock = 8;  // 4x4 blocks of the 32x32 render
constexpr int kResolution = 32;
constexpr uint32_t kSamplesPerPixel = 512;
// Two-sided bound for 16 blocks at a family-wise false-alarm rate of ~1e-3 (Šidák).
constexpr double kZBound = 4.0;

TEST(PbrtManyLights, RendersWithTheHierarchyAndMatchesThePowerSampler) {
  SceneDesc s = load_scene(std::string(KILN_SOURCE_DIR) + "/tests/data/pbrt/many_lights.pbrt");
  s.cameras.at(0).width = s.cameras[0].height = kResolution;
  const auto bvh = build_world(s, {});
  const LightSamplerStats& st = bvh->stats.light_sampler;
  EXPECT_EQ(st.kind, LightSamplerKind::Bvh);
  EXPECT_EQ(st.emitters, 48u * 2u);
  WorldOptions wo;
  wo.light_sampler = LightSamplerKind::Power;
  const auto power = build_world(s, wo);
  const IntegratorSettings settings = camera_settings(s.cameras[0], s, s.rules, {}, bvh->features);
  const auto a = block_estimates(*bvh, s.cameras[0], settings, kSamplesPerPixel, 1, kBlock);
  const auto b = block_estimates(*power, s.cameras[0], settings, kSamplesPerPixel, 2, kBlock);
  const Worst w = worst_block(a, b);
  ASSERT_GE(w.block, 0);
  EXPECT_LT(w.z, kZBound) << "block " << w.block << ": bvh " << a[size_t(w.block)].mean << " +- "
                          << a[size_t(w.block)].stderr_ << ", power " << b[size_t(w.block)].mean << " +- "
                          << b[size_t(w.block)].stderr_;
  // The lamps light the room (a lamp facing the wrong way would leave the floor dark).
  EXPECT_GT(a[size_t(a.size() - 2)].mean, 0.05);
  std::printf("worst block %d at |z| = %.1f\n", w.block, w.z);
}

}  // namespace
}  // namespace kiln::test
