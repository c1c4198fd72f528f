// End to end through the path tracer: the furnace box (a closed cube emitting Le inward) lined with pbrt-v4
// reflection-only materials, built from MaterialDesc::pbrt by the material mapping.
//  * A white base under a thin smooth coat reflects exactly 1 at every angle (with a long enough walk), so D bounces
//    give (D + 1) Le for BSDF sampling, NEE and MIS alike: this checks the coat's specular samples coming from a
//    surface lobe and the layered BxDF's estimated pdf inside MIS.
//  * Rough conductors and rough coats reflect less than 1 by an amount with no closed form, so BSDF-only, NEE and
//    MIS estimates of the same furnace must agree with each other (each uses a different mix of sample(), eval()
//    and pdf()).
#include <gtest/gtest.h>

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
  // One bounce: the NEE-only estimate is then eval() alone against sample() alone for BSDF sampling, with the
  // least variance from the light sampling of later bounces.
  constexpr int kDepth = 1;
  for (const auto& [name, d] : cases) {
    const SceneDesc scene = pbrt_furnace(d);
    const auto world = build_world(scene, {});
    std::vector<Estimate> est;
    for (const Strategy& st : kStrategies)
      est.push_back(estimate_mean(*world, strategy(st.nee, st.mis, st.rr, kDepth), scene.cameras[0], 200000, 11));
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

// A rough dielectric pane (one open quad, like a thin window) inside the furnace, facing the camera: light reaches
// its front through the pane's transmission lobe, so NEE must sample lights behind the surface (the shading frame
// and the geometry agree that the direction transmits) and MIS must weight those samples against BSDF-sampled
// transmission. BSDF sampling, NEE and MIS agree; so do the uniform and cosine strategies, which sample a surface
// with transmission by its BSDF.
TEST(PbrtFurnace, StrategiesAgreeThroughARoughDielectricPane) {
  SceneDesc scene = furnace_box(0.5f, Rgb(1.0f));
  PbrtMaterialDesc glass;
  glass.kind = PbrtMaterialKind::Dielectric;
  glass.eta = 1.5f;
  glass.uroughness = glass.vroughness = 0.3f;
  MaterialDesc pane_material;
  pane_material.pbrt = glass;
  scene.materials.push_back(pane_material);
  MeshDesc pane;
  pane.name = "pane";
  pane.positions = {{-0.9f, -0.9f, -0.4f}, {0.9f, -0.9f, -0.4f}, {0.9f, 0.9f, -0.4f}, {-0.9f, 0.9f, -0.4f}};
  pane.indices = {0, 1, 2, 0, 2, 3};
  pane.material = 1;
  scene.meshes.push_back(pane);
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
