// Every light sampler estimates the same image (lights/light_sampler.h): on a room lit by many small ceiling lamps
// of 100x different power (with a point, a spot and a sphere light among them) and on a room lit by an emissive
// killeroo (8,316 triangles, which the hierarchy holds triangle by triangle), the block means of the hierarchy's and
// the uniform sampler's renders are compared with the power sampler's, block by block, against the noise both carry
// (as tests/renderer/integrators/strategy_agreement_test.cpp does for strategies). The hierarchy is also run with
// NEE alone (no MIS), where a light it wrongly gave probability 0 could not be made up for by BSDF sampling. Its
// renders are bit-identical for any thread count and tile order.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "renderer/integrators/stability_util.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

constexpr int kResolution = 16;
constexpr int kBlock = 4;
constexpr int kMaxDepth = 3;
constexpr uint32_t kSamplesPerPixel = 2048;
constexpr uint32_t kReferenceSamplesPerPixel = 4096;
// Two-sided bound for 16 blocks x 4 comparisons x 2 scenes at a family-wise false-alarm rate of ~1e-3 (Šidák).
constexpr double kZBound = 4.5;
constexpr uint64_t kReferenceSeed = 1000;

// The Cornell box without its light and spheres' glass: diffuse and glossy surfaces only.
SceneDesc dark_box() {
  SceneDesc s = cornell_box(BoxPlacement{}, kResolution);
  std::erase_if(s.meshes, [](const MeshDesc& m) { return m.name == "light"; });
  return s;
}

// 48 small lamps just below the ceiling, radiance spanning 100x in random colours; a point light, a spot light and a
// sphere light among them.
SceneDesc many_lights_room() {
  SceneDesc s = dark_box();
  const BoxPlacement at;
  Rng rng(31, 7);
  for (int i = 0; i < 48; ++i) {
    const float x = -220.0f + 440.0f * rng.next_float(), z = -220.0f + 440.0f * rng.next_float(), h = 12.0f;
    MeshDesc lamp = quad_mesh("lamp" + std::to_string(i), at.at(x - h, 255, z - h), at.at(x + h, 255, z - h),
                              at.at(x + h, 255, z + h), at.at(x - h, 255, z + h), -1);
    const float power = 2.0f * std::pow(10.0f, 2.0f * rng.next_float());
    lamp.emission = Rgb(power * (0.2f + rng.next_float()), power * (0.2f + rng.next_float()), power * (0.2f + rng.next_float()));
    s.meshes.push_back(lamp);
  }
  PointLightDesc point;
  point.position = at.at(-150, 150, 100);
  point.intensity = Rgb(0.05f);
  s.point_lights.push_back(point);
  SpotLightDesc spot;
  spot.position = at.at(150, 200, 0);
  spot.direction = {0, -1, 0};
  spot.intensity = Rgb(0.2f);
  spot.coverage_deg = 80.0f;
  spot.falloff_deg = 30.0f;
  s.spot_lights.push_back(spot);
  SphereDesc bulb;
  bulb.name = "bulb";
  bulb.center = at.at(0, 180, -200);
  bulb.radius = 10.0f * at.unit;
  bulb.material = -1;
  bulb.emission = Rgb(20.0f);
  s.spheres.push_back(bulb);
  return s;
}

// The bundled killeroo (8,316 triangles) standing on the floor and glowing, beside a dim ceiling lamp.
SceneDesc emissive_killeroo_room() {
  SceneDesc s = dark_box();
  const SceneDesc k = load_scene(KILN_SOURCE_DIR "/scenes/killeroo/killeroo.ply");
  MeshDesc m = k.meshes.at(0);
  Bounds3f b;
  for (const Vec3f& p : m.positions) b.extend(p);
  const float scale = 300.0f / max_component(b.diagonal()) / kBoxGrid;
  const Vec3f c = b.center();
  for (Vec3f& p : m.positions) {
    const Vec3f q = (p - c) * scale;  // Z-up model: stand it up along +y
    p = Vec3f(q.x, q.z + 0.5f * b.diagonal().z * scale - 255.0f / kBoxGrid, -q.y);
  }
  m.name = "killeroo";
  m.material = kWhite;
  m.emission = Rgb(1.5f, 1.0f, 0.6f);
  m.two_sided_emission = true;  // whatever the model's winding, it glows outwards
  s.meshes.push_back(m);
  const BoxPlacement at;
  MeshDesc lamp = quad_mesh("lamp", at.at(-32, 255, -32), at.at(32, 255, -32), at.at(32, 255, 32), at.at(-32, 255, 32), -1);
  lamp.emission = Rgb(2.0f);
  s.meshes.push_back(lamp);
  return s;
}

std::unique_ptr<World> world_with(const SceneDesc& s, LightSamplerKind kind) {
  WorldOptions wo;
  wo.light_sampler = kind;
  return build_world(s, wo);
}

PathSettings strategy(const char* name) {
  PathSettings base;
  base.max_depth = kMaxDepth;
  base.russian_roulette = false;
  return kiln_strategy(name, base, "strategy");
}

// Each sampler's blocks against the power sampler's (MIS), worst |z| below the bound.
void expect_samplers_agree(const SceneDesc& s, const char* scene_name) {
  const auto power = world_with(s, LightSamplerKind::Power);
  const auto reference = block_estimates(*power, s.cameras[0], strategy("mis"), kReferenceSamplesPerPixel,
                                         kReferenceSeed, kBlock);
  struct Case {
    LightSamplerKind kind;
    const char* strategy;
  };
  uint64_t seed = 1;
  for (const Case c : {Case{LightSamplerKind::Bvh, "mis"}, Case{LightSamplerKind::Bvh, "nee"},
                       Case{LightSamplerKind::Uniform, "mis"}, Case{LightSamplerKind::Power, "nee"}}) {
    const auto w = world_with(s, c.kind);
    const auto blocks = block_estimates(*w, s.cameras[0], strategy(c.strategy), kSamplesPerPixel, seed++, kBlock);
    const Worst worst = worst_block(blocks, reference);
    ASSERT_GE(worst.block, 0);
    const std::string name = std::string(scene_name) + " " + light_sampler_name(c.kind) + " " + c.strategy;
    EXPECT_LT(worst.z, kZBound) << name << ": block " << worst.block << " mean " << blocks[size_t(worst.block)].mean
                                << " +- " << blocks[size_t(worst.block)].stderr_ << ", power "
                                << reference[size_t(worst.block)].mean << " +- " << reference[size_t(worst.block)].stderr_;
    std::printf("%-28s worst block %2d at |z| = %.1f\n", name.c_str(), worst.block, worst.z);
  }
}

TEST(LightSamplerAgreement, ManyLightsRoom) {
  const SceneDesc s = many_lights_room();
  EXPECT_EQ(world_with(s, LightSamplerKind::Bvh)->stats.light_sampler.emitters, 48u * 2u + 3u);
  expect_samplers_agree(s, "many lights");
}

TEST(LightSamplerAgreement, EmissiveKillerooMesh) {
  const SceneDesc s = emissive_killeroo_room();
  const auto w = build_world(s, {});
  EXPECT_EQ(w->stats.light_sampler.kind, LightSamplerKind::Bvh);  // the default for a large emissive mesh
  EXPECT_EQ(w->stats.light_sampler.emitters, 8316u + 2u);
  expect_samplers_agree(s, "emissive killeroo");
}

// Same seed, same pixels for any thread count and tile order with the hierarchy choosing among the killeroo's
// triangles, where MIS asks pmf() at every BSDF ray that hits the glowing mesh (a sampler keeping per-thread state
// between pixels would show here; the pbrt room's small lamps are hit too rarely).
TEST(LightSamplerAgreement, HierarchyRendersAreBitIdenticalForAnyThreadCount) {
  const SceneDesc s = emissive_killeroo_room();
  const auto w = world_with(s, LightSamplerKind::Bvh);
  const PathSettings mis = strategy("mis");
  constexpr uint32_t kSpp = 8;
  const Image one = render_image(*w, s.cameras[0], mis, kSpp, 7, 1);
  const Image two = render_image(*w, s.cameras[0], mis, kSpp, 7, 2, true);
  ASSERT_EQ(one.pixels().size(), two.pixels().size());
  for (size_t i = 0; i < one.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(one.pixels()[i][c], two.pixels()[i][c]) << "pixel " << i;
}

}  // namespace
}  // namespace kiln::test
