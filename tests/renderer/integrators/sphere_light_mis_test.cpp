// A sphere light (and an ellipsoid: the same sphere under a non-uniform scale) large enough that BRDF-sampled
// rays hit it often, in a small Cornell box with a glossy floor and block. BRDF sampling alone finds the light only
// by hitting it, so it never calls the light's sampler or its pdf; NEE uses only sample_li; MIS weighs both with
// pdf_li. All three must agree block by block: a wrong solid-angle density (pdf_li or sample_li's pdf) biases NEE
// or the MIS weights but not BRDF sampling. (Stiff.TinyBrightLightNextToADimOne cannot see that: its light is too
// small for a BRDF ray to hit.)
#include <gtest/gtest.h>

#include <cstdio>

#include "renderer/integrators/stability_util.h"

namespace kiln::test {
namespace {

constexpr int kResolution = 16;
constexpr int kBlock = 4;
constexpr int kMaxDepth = 3;
// Brdf-only runs carry more noise (the light is found by chance), so they get more samples; the reference is one
// of them (the strategy that cannot depend on the light's pdf).
constexpr uint32_t kSppWithNee = 2048;
constexpr uint32_t kSppBrdfOnly = 8192;
// Two-sided z bound for 16 blocks x 6 comparisons at a family-wise false-alarm rate of ~1e-3 (Šidák, as in
// strategy_agreement_test.cpp).
constexpr double kZBound = 4.5;
constexpr float kLightRadius = 70.0f;  // grid units (box half-size 256)
constexpr float kLightRadiance = 4.0f;

SceneDesc sphere_light_box(Vec3f ellipsoid_scale) {
  const BoxPlacement at;
  SceneDesc s = cornell_box(at, kResolution);
  std::erase_if(s.meshes, [](const MeshDesc& m) { return m.name == "light"; });
  for (MeshDesc& m : s.meshes)
    if (m.name == "floor") m.material = kGlossy;
  for (SphereDesc& sp : s.spheres) sp.material = kWhite;  // no glass: caustics would need far more samples
  SphereDesc light;
  light.name = "Sphere light";
  light.radius = kLightRadius * at.unit;
  const Vec3f c = at.at(-30, 150, -20);
  // world = to_world * translate(center) * scale(radius): scale about the light's centre.
  light.to_world = Transform::translate(c) * Transform::scale(ellipsoid_scale);
  light.emission = Rgb(kLightRadiance);
  s.spheres.push_back(light);
  return s;
}

struct Case {
  const char* name;
  Vec3f scale;
};

class SphereLightMis : public ::testing::TestWithParam<Case> {};

TEST_P(SphereLightMis, NeeAndMisAgreeWithBrdfSamplingBlockByBlock) {
  const SceneDesc scene = sphere_light_box(GetParam().scale);
  const auto world = build_world(scene, {});  // Kiln's rules: the exact ellipsoid density
  PathSettings base;
  base.max_depth = kMaxDepth;
  base.russian_roulette = false;
  const auto strategy = [&](const char* name) { return kiln_strategy(name, base, "strategy"); };
  const CameraDesc& cam = scene.cameras[0];
  const auto reference = block_estimates(*world, cam, strategy("brdf"), kSppBrdfOnly, 101, kBlock);
  double lit = 0;
  for (const Estimate& e : reference) lit += e.mean;
  ASSERT_GT(lit, 0.0) << "BRDF-sampled rays must reach the light";
  uint64_t seed = 1;
  for (const char* s : {"nee", "mis"}) {
    PathSettings st = strategy(s);
    const auto blocks = block_estimates(*world, cam, st, kSppWithNee, seed++, kBlock);
    const Worst w = worst_block(blocks, reference);
    ASSERT_GE(w.block, 0);
    EXPECT_LT(w.z, kZBound) << s << ": block " << w.block << " mean " << blocks[size_t(w.block)].mean << " +- "
                            << blocks[size_t(w.block)].stderr_ << ", brdf " << reference[size_t(w.block)].mean;
    std::printf("%s %-4s worst block %2d at |z| = %.1f\n", GetParam().name, s, w.block, w.z);
  }
  // MIS with uniform hemisphere directions: other BSDF pdfs in the weights, the same light pdf.
  PathSettings uniform = strategy("mis");
  uniform.directions = DirectionSampling::Uniform;
  const Worst w = worst_block(block_estimates(*world, cam, uniform, kSppWithNee, seed++, kBlock), reference);
  EXPECT_LT(w.z, kZBound) << "mis, uniform directions: block " << w.block;
  std::printf("%s mis (uniform directions) worst block %2d at |z| = %.1f\n", GetParam().name, w.block, w.z);
}

INSTANTIATE_TEST_SUITE_P(Lights, SphereLightMis,
                         ::testing::Values(Case{"sphere", {1.0f, 1.0f, 1.0f}}, Case{"ellipsoid", {1.8f, 0.6f, 1.2f}}),
                         [](const auto& tp) { return std::string(tp.param.name); });

}  // namespace
}  // namespace kiln::test
