// End to end through the path tracer: the furnace box (a closed cube emitting Le inward) lined with pbrt-v4
// reflection-only materials, built from MaterialDesc::pbrt by the material mapping.
//  * A white base under a thin smooth coat reflects exactly 1 at every angle (with a long enough walk), so D bounces
//    give (D + 1) Le for BSDF sampling, NEE and MIS alike: this checks the coat's specular samples coming from a
//    surface lobe and the layered BxDF's estimated pdf inside MIS.
//  * Rough conductors and rough coats reflect less than 1 by an amount with no closed form, so BSDF-only, NEE and
//    MIS estimates of the same furnace must agree with each other (each uses a different mix of sample(), eval()
//    and pdf()).
#include <gtest/gtest.h>

#include "core/error.h"
#include "renderer/render_util.h"

namespace kiln::test {
namespace {

SceneDesc pbrt_furnace(const PbrtMaterialDesc& d) {
  SceneDesc s = furnace_box(0.5f, Rgb(1.0f));
  s.materials[0].pbrt = d;
  return s;
}

PathSettings strategy(bool nee, bool mis, bool rr, int max_depth) {
  PathSettings s;
  s.directions = DirectionSampling::Brdf;
  s.nee = nee;
  s.mis = mis;
  s.russian_roulette = rr;
  s.rr_min_depth = 1;
  s.max_depth = max_depth;
  return s;
}

struct Strategy {
  const char* name;
  bool nee, mis, rr;
};
constexpr Strategy kStrategies[] = {
    {"brdf", false, false, false}, {"nee", true, false, false}, {"mis", true, true, false}, {"mis_rr", true, true, true}};

TEST(PbrtFurnace, WhiteBaseUnderSmoothCoatGivesDPlusOne) {
  PbrtMaterialDesc d;
  d.kind = PbrtMaterialKind::CoatedDiffuse;
  d.reflectance = Rgb(1.0f);
  d.thickness = 0.0f;  // no absorption in the layer
  d.max_depth = 400;   // walk truncation below 1e-40
  const SceneDesc scene = pbrt_furnace(d);
  const auto world = build_world(scene, {});
  constexpr int kDepth = 3;
  for (const Strategy& st : kStrategies) {
    const Estimate e = estimate_mean(*world, strategy(st.nee, st.mis, st.rr, kDepth), scene.cameras[0], 100000);
    EXPECT_NEAR(e.mean, kDepth + 1.0, 4.5 * e.stderr_ + 1e-4) << st.name << ": " << e.mean << " +- " << e.stderr_;
  }
}

// BSDF sampling, NEE, MIS and MIS with roulette give the same one-bounce furnace for each material, at most 2.
void expect_strategies_agree(const std::vector<std::pair<std::string, PbrtMaterialDesc>>& cases, uint32_t samples) {
  // One bounce: the NEE-only estimate is then eval() alone against sample() alone for BSDF sampling, with the
  // least variance from the light sampling of later bounces.
  constexpr int kDepth = 1;
  for (const auto& [name, d] : cases) {
    const SceneDesc scene = pbrt_furnace(d);
    const auto world = build_world(scene, {});
    std::vector<Estimate> est;
    for (const Strategy& st : kStrategies)
      est.push_back(estimate_mean(*world, strategy(st.nee, st.mis, st.rr, kDepth), scene.cameras[0], samples, 11));
    for (size_t a = 0; a < est.size(); ++a)
      for (size_t b = a + 1; b < est.size(); ++b) {
        const double se = std::hypot(est[a].stderr_, est[b].stderr_);
        EXPECT_NEAR(est[a].mean, est[b].mean, 4.5 * se) << name << ": " << kStrategies[a].name << " " << est[a].mean
                                                         << " vs " << kStrategies[b].name << " " << est[b].mean;
      }
    // Energy: D bounces of an albedo <= 1 material give at most D + 1.
    for (const Estimate& e : est) EXPECT_LE(e.mean, kDepth + 1.0 + 4.5 * e.stderr_) << name;
  }
}

TEST(PbrtFurnace, StrategiesAgreeOnRoughMaterials) {
  std::vector<std::pair<std::string, PbrtMaterialDesc>> cases;
  PbrtMaterialDesc gold;
  gold.kind = PbrtMaterialKind::Conductor;
  gold.conductor_eta = Rgb(0.143f, 0.374f, 1.442f);
  gold.conductor_k = Rgb(3.983f, 2.385f, 1.603f);
  gold.uroughness = gold.vroughness = 0.1f;
  cases.push_back({"rough_gold", gold});
  PbrtMaterialDesc coat;  // the killeroo's rougher coat
  coat.kind = PbrtMaterialKind::CoatedDiffuse;
  coat.reflectance = Rgb(0.4f, 0.5f, 0.4f);
  coat.uroughness = coat.vroughness = 0.15f;
  cases.push_back({"killeroo_coat", coat});
  PbrtMaterialDesc bright = coat;  // the same coat over a bright base: the most light crosses the coat
  bright.reflectance = Rgb(0.9f);
  cases.push_back({"bright_coat", bright});
  PbrtMaterialDesc medium = coat;
  medium.thickness = 0.3f;
  medium.albedo = Rgb(0.8f);
  medium.g = 0.4f;
  cases.push_back({"coat_with_medium", medium});
  expect_strategies_agree(cases, 200000);
}

TEST(PbrtFurnace, StrategiesAgreeOnCoatedConductors) {
  std::vector<std::pair<std::string, PbrtMaterialDesc>> cases;
  PbrtMaterialDesc coated_gold;  // the feature scene's coated gold
  coated_gold.kind = PbrtMaterialKind::CoatedConductor;
  coated_gold.conductor_eta = Rgb(0.143f, 0.374f, 1.442f);
  coated_gold.conductor_k = Rgb(3.983f, 2.385f, 1.603f);
  coated_gold.uroughness = coated_gold.vroughness = 0.02f;
  coated_gold.conductor_uroughness = coated_gold.conductor_vroughness = 0.1f;
  cases.push_back({"coated_gold", coated_gold});
  PbrtMaterialDesc rough_over_mirror = coated_gold;  // a smooth base: its delta bounce inside a rough coat
  rough_over_mirror.uroughness = rough_over_mirror.vroughness = 0.2f;
  rough_over_mirror.conductor_uroughness = rough_over_mirror.conductor_vroughness = 0.0f;
  cases.push_back({"rough_coat_smooth_gold", rough_over_mirror});
  expect_strategies_agree(cases, 100000);
}

// A pane (one open quad) of `material` inside the furnace, facing the camera.
SceneDesc furnace_with_pane(const PbrtMaterialDesc& material) {
  SceneDesc scene = furnace_box(0.5f, Rgb(1.0f));
  MaterialDesc pane_material;
  pane_material.pbrt = material;
  scene.materials.push_back(pane_material);
  MeshDesc pane;
  pane.name = "pane";
  pane.positions = {{-0.9f, -0.9f, -0.4f}, {0.9f, -0.9f, -0.4f}, {0.9f, 0.9f, -0.4f}, {-0.9f, 0.9f, -0.4f}};
  pane.indices = {0, 1, 2, 0, 2, 3};
  pane.material = 1;
  scene.meshes.push_back(pane);
  return scene;
}

// Thin surfaces that lose no energy (diffuse transmission with R + T = 1, a thin dielectric) leave the furnace's
// uniform radiance 1 / (1 - 0.5) = 2 unchanged, from either side: light reaches the camera through them, NEE must
// find the walls behind them, and a transmitted path changes no medium.
TEST(PbrtFurnace, LosslessThinPanesAreInvisible) {
  PbrtMaterialDesc translucent;
  translucent.kind = PbrtMaterialKind::DiffuseTransmission;
  translucent.reflectance = Rgb(0.6f, 0.3f, 0.5f);
  translucent.transmittance = Rgb(0.4f, 0.7f, 0.5f);
  PbrtMaterialDesc window;
  window.kind = PbrtMaterialKind::ThinDielectric;
  window.eta = 1.5f;
  for (const auto& [name, material] : {std::pair{"diffuse_transmission", translucent}, std::pair{"thin_dielectric", window}}) {
    const SceneDesc scene = furnace_with_pane(material);
    const auto world = build_world(scene, {});
    EXPECT_FALSE(world->features & kFeatureDielectric) << name;  // two-sided: no media are tracked
    for (const Strategy& st : kStrategies) {
      PathSettings s = strategy(st.nee, st.mis, true, -1);
      const Estimate e = estimate_mean(*world, s, scene.cameras[0], 100000, 31);
      EXPECT_NEAR(e.mean, 2.0, 4.5 * e.stderr_) << name << " " << st.name << ": " << e.mean << " +- " << e.stderr_;
    }
  }
}

// A lossy diffuse-transmission pane: BSDF sampling, NEE and MIS (and the uniform and cosine strategies, which sample
// a transmitting surface by its BSDF) agree.
TEST(PbrtFurnace, StrategiesAgreeThroughADiffuseTransmissionPane) {
  PbrtMaterialDesc translucent;
  translucent.kind = PbrtMaterialKind::DiffuseTransmission;
  translucent.reflectance = Rgb(0.3f, 0.5f, 0.3f);
  translucent.transmittance = Rgb(0.5f, 0.3f, 0.2f);
  const SceneDesc scene = furnace_with_pane(translucent);
  const auto world = build_world(scene, {});
  constexpr int kDepth = 2;
  std::vector<Estimate> est;
  for (const DirectionSampling dirs : {DirectionSampling::Brdf, DirectionSampling::Cosine, DirectionSampling::Uniform})
    for (const Strategy& st : kStrategies) {
      PathSettings s = strategy(st.nee, st.mis, st.rr, kDepth);
      s.directions = dirs;
      est.push_back(estimate_mean(*world, s, scene.cameras[0], 100000, 41 + est.size()));
    }
  for (size_t i = 1; i < est.size(); ++i) {
    const double se = std::hypot(est[0].stderr_, est[i].stderr_);
    EXPECT_NEAR(est[i].mean, est[0].mean, 4.5 * se) << "strategy " << i << " " << est[i].mean << " vs " << est[0].mean;
  }
}

// A mix chooses one component per hit with probability `amount`, independently at each bounce: a furnace lined with
// mix(a, b, t) gives sum_{k=0..D} abar^k with abar = (1 - t) a + t b, the blend in expectation; nested mixes too.
TEST(PbrtFurnace, MixIsTheBlendInExpectation) {
  const auto diffuse = [](float albedo) {
    MaterialDesc m;
    PbrtMaterialDesc d;
    d.reflectance = Rgb(albedo);
    m.pbrt = d;
    return m;
  };
  const auto mix = [](int a, int b, float amount) {
    MaterialDesc m;
    m.mix = MaterialMixDesc{{a, b}, amount};
    return m;
  };
  struct Case {
    const char* name;
    std::vector<MaterialDesc> materials;  // the last one lines the furnace
    double abar;
  };
  const Case cases[] = {
      {"mix", {diffuse(0.2f), diffuse(0.8f), mix(0, 1, 0.25f)}, 0.75 * 0.2 + 0.25 * 0.8},
      {"nested", {diffuse(0.2f), diffuse(0.8f), diffuse(0.9f), mix(0, 1, 0.5f), mix(3, 2, 0.4f)},
       0.6 * (0.5 * 0.2 + 0.5 * 0.8) + 0.4 * 0.9},
      {"amount_one", {diffuse(0.2f), diffuse(0.8f), mix(0, 1, 1.0f)}, 0.8},
  };
  constexpr int kDepth = 3;
  for (const Case& c : cases) {
    SceneDesc scene = furnace_box(0.5f, Rgb(1.0f));
    scene.materials = c.materials;
    scene.meshes[0].material = int(c.materials.size()) - 1;
    const auto world = build_world(scene, {});
    ASSERT_TRUE(world->features & kFeatureMix) << c.name;
    const double expected = 1 + c.abar + c.abar * c.abar + c.abar * c.abar * c.abar;
    for (const Strategy& st : kStrategies) {
      const Estimate e = estimate_mean(*world, strategy(st.nee, st.mis, st.rr, kDepth), scene.cameras[0], 100000, 51);
      // (+ float rounding: with amount 1 every path has the same weight)
      EXPECT_NEAR(e.mean, expected, 4.5 * e.stderr_ + 1e-6) << c.name << " " << st.name << ": " << e.mean << " +- "
                                                             << e.stderr_;
    }
  }
}

TEST(PbrtFurnace, MixCyclesAreRejected) {
  SceneDesc scene = furnace_box(0.5f, Rgb(1.0f));
  MaterialDesc a, b;
  a.mix = MaterialMixDesc{{0, 2}, 0.5f};
  b.mix = MaterialMixDesc{{1, 0}, 0.5f};
  scene.materials.push_back(a);
  scene.materials.push_back(b);
  try {
    build_world(scene, {});
    FAIL() << "a cycle of mixes built";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("mix materials contain each other"), std::string::npos) << e.what();
  }
}

// A rough dielectric pane (one open quad, like a thin window) inside the furnace, facing the camera: light reaches
// its front through the pane's transmission lobe, so NEE must sample lights behind the surface (the shading frame
// and the geometry agree that the direction transmits) and MIS must weight those samples against BSDF-sampled
// transmission. BSDF sampling, NEE and MIS agree; so do the uniform and cosine strategies, which sample a surface
// with transmission by its BSDF.
TEST(PbrtFurnace, StrategiesAgreeThroughARoughDielectricPane) {
  PbrtMaterialDesc glass;
  glass.kind = PbrtMaterialKind::Dielectric;
  glass.eta = 1.5f;
  glass.uroughness = glass.vroughness = 0.3f;
  const SceneDesc scene = furnace_with_pane(glass);
  const auto world = build_world(scene, {});
  ASSERT_TRUE(world->features & kFeatureDielectric);  // oriented: media tracked, normals not flipped
  constexpr int kDepth = 2;
  struct Case {
    const char* name;
    DirectionSampling dirs;
    bool nee, mis;
  };
  const Case cases[] = {{"brdf", DirectionSampling::Brdf, false, false},
                        {"nee", DirectionSampling::Brdf, true, false},
                        {"mis", DirectionSampling::Brdf, true, true},
                        {"cosine", DirectionSampling::Cosine, false, false},
                        {"uniform_mis", DirectionSampling::Uniform, true, true}};
  std::vector<Estimate> est;
  for (const Case& c : cases) {
    PathSettings s = strategy(c.nee, c.mis, false, kDepth);
    s.directions = c.dirs;
    est.push_back(estimate_mean(*world, s, scene.cameras[0], 200000, 21 + est.size()));
  }
  for (size_t i = 1; i < est.size(); ++i) {
    const double se = std::hypot(est[0].stderr_, est[i].stderr_);
    EXPECT_NEAR(est[i].mean, est[0].mean, 4.5 * se)
        << cases[i].name << " " << est[i].mean << " vs brdf " << est[0].mean << " +- " << se;
  }
}

// pbrt's "interface" material marks a boundary between media and scatters nothing: without media Kiln leaves such
// shapes out of the world, so a furnace with an interface sphere in front of the camera renders the furnace.
TEST(PbrtFurnace, InterfaceShapesAreLeftOut) {
  SceneDesc plain = furnace_box(0.5f, Rgb(1.0f));
  SceneDesc with_interface = plain;
  PbrtMaterialDesc boundary;
  boundary.kind = PbrtMaterialKind::Interface;
  MaterialDesc m;
  m.pbrt = boundary;
  with_interface.materials.push_back(m);
  SphereDesc sphere;
  sphere.name = "interface sphere";
  sphere.center = {0.1f, -0.2f, -0.5f};
  sphere.radius = 0.3f;
  sphere.material = 1;
  with_interface.spheres.push_back(sphere);
  const auto a = build_world(plain, {});
  const auto b = build_world(with_interface, {});
  EXPECT_EQ(b->stats.interface_shapes, 1u);
  EXPECT_EQ(b->geometry.shapes.size(), a->geometry.shapes.size());
  const PathSettings s = strategy(true, true, false, 3);
  const Estimate ea = estimate_mean(*a, s, plain.cameras[0], 20000, 5);
  const Estimate eb = estimate_mean(*b, s, with_interface.cameras[0], 20000, 5);
  EXPECT_EQ(ea.mean, eb.mean);
}

}  // namespace
}  // namespace kiln::test
