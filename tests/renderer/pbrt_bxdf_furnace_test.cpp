// End to end through the path tracer: the furnace box (a closed cube emitting Le inward) lined with pbrt-v4
// reflection-only materials, built from MaterialDesc::pbrt by the material mapping.
//  * A white base under a thin smooth coat reflects exactly 1 at every angle (with a long enough walk), so D bounces
//    give (D + 1) Le for BSDF sampling, NEE and MIS alike: this checks the coat's specular samples coming from a
//    surface lobe and the layered BxDF's estimated pdf inside MIS.
//  * Rough conductors and rough coats reflect less than 1 by an amount with no closed form, so BSDF-only, NEE and
//    MIS estimates of the same furnace must agree with each other (each uses a different mix of sample(), eval()
//    and pdf()).
#include <gtest/gtest.h>

#include "render_util.h"

namespace kiln::test {
namespace {

SceneDesc pbrt_furnace(const PbrtMaterialDesc& d) {
  SceneDesc s = furnace_box(0.5f, Rgb(1.0f));
  s.materials[0].pbrt = d;
  return s;
}

IntegratorSettings strategy(bool nee, bool mis, bool rr, int max_depth) {
  IntegratorSettings s;
  s.kind = RendererKind::PathTracing;
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

}  // namespace
}  // namespace kiln::test
