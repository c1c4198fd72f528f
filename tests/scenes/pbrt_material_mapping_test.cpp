// scenes/material_mapping for pbrt-v4 materials (MaterialDesc::pbrt): which Kiln BxDF each pbrt material and
// parameter set becomes, pbrt's roughness remapping and conductor "reflectance" form, and the errors for bad values.
#include <gtest/gtest.h>

#include "core/error.h"
#include "scenes/material_mapping.h"

namespace kiln {
namespace {

SceneDesc pbrt_scene() {
  SceneDesc s;
  s.source_path = "scene.pbrt";
  return s;
}

MaterialDesc pbrt_material(PbrtMaterialDesc d) {
  MaterialDesc m;
  m.id = 3;
  m.pbrt = d;
  return m;
}

PbrtMaterialDesc of_kind(PbrtMaterialKind k) {
  PbrtMaterialDesc d;
  d.kind = k;
  return d;
}

std::string error_of(const PbrtMaterialDesc& d) {
  try {
    build_material(pbrt_material(d), pbrt_scene());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PbrtMaterialMapping, DiffuseIsClampedLambert) {
  PbrtMaterialDesc d = of_kind(PbrtMaterialKind::Diffuse);
  d.reflectance = Rgb(0.2f, 0.5f, 1.7f);
  const Material m = build_material(pbrt_material(d), pbrt_scene());
  ASSERT_TRUE(std::holds_alternative<Lambert>(m.surface));
  EXPECT_EQ(std::get<Lambert>(m.surface).reflectance, Rgb(0.2f, 0.5f, 1.0f));
  EXPECT_FALSE(m.has_delta());
}

TEST(PbrtMaterialMapping, ConductorSmoothIsDeltaWithRgbIor) {
  PbrtMaterialDesc d = of_kind(PbrtMaterialKind::Conductor);
  d.conductor_eta = Rgb(0.2f, 0.9f, 1.1f);
  d.conductor_k = Rgb(3.9f, 2.4f, 2.1f);
  const Material m = build_material(pbrt_material(d), pbrt_scene());
  ASSERT_TRUE(std::holds_alternative<Conductor>(m.delta));
  EXPECT_FALSE(m.has_surface());
  const Conductor& c = std::get<Conductor>(m.delta);
  ASSERT_TRUE(c.rgb_ior);
  EXPECT_EQ(c.rgb_ior->eta, d.conductor_eta);
  EXPECT_EQ(c.rgb_ior->k, d.conductor_k);
  EXPECT_EQ(c.reflectance, Rgb(1.0f));
  // A roughness whose alpha stays below pbrt's smooth threshold (sqrt(5e-7) < 1e-3) is still a mirror.
  d.uroughness = d.vroughness = 5e-7f;
  EXPECT_TRUE(std::holds_alternative<Conductor>(build_material(pbrt_material(d), pbrt_scene()).delta));
}

TEST(PbrtMaterialMapping, ConductorRoughnessIsRemapped) {
  PbrtMaterialDesc d = of_kind(PbrtMaterialKind::Conductor);
  d.uroughness = 0.16f;
  d.vroughness = 0.04f;
  Material m = build_material(pbrt_material(d), pbrt_scene());
  ASSERT_TRUE(std::holds_alternative<RoughConductor>(m.surface));
  EXPECT_FALSE(m.has_delta());
  EXPECT_FLOAT_EQ(std::get<RoughConductor>(m.surface).distribution.alpha_x, 0.4f);
  EXPECT_FLOAT_EQ(std::get<RoughConductor>(m.surface).distribution.alpha_y, 0.2f);
  d.remap_roughness = false;
  m = build_material(pbrt_material(d), pbrt_scene());
  EXPECT_FLOAT_EQ(std::get<RoughConductor>(m.surface).distribution.alpha_x, 0.16f);
  EXPECT_FLOAT_EQ(std::get<RoughConductor>(m.surface).distribution.alpha_y, 0.04f);
}

TEST(PbrtMaterialMapping, ConductorReflectanceFormHasThatNormalReflectance) {
  PbrtMaterialDesc d = of_kind(PbrtMaterialKind::Conductor);
  d.conductor_reflectance = Rgb(0.9f, 0.5f, 0.1f);
  d.uroughness = d.vroughness = 0.1f;
  const Material m = build_material(pbrt_material(d), pbrt_scene());
  ASSERT_TRUE(std::holds_alternative<RoughConductor>(m.surface));
  const RgbComplexIor& ior = std::get<RoughConductor>(m.surface).ior;
  EXPECT_EQ(ior.eta, Rgb(1.0f));
  const Rgb r0 = fresnel_conductor(1.0f, ior);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r0[c], (*d.conductor_reflectance)[c], 1e-5f);
  // r = 1 would need k = infinity: pbrt clamps to 0.9999.
  d.conductor_reflectance = Rgb(1.0f);
  const Material one = build_material(pbrt_material(d), pbrt_scene());
  EXPECT_TRUE(std::isfinite(std::get<RoughConductor>(one.surface).ior.k.r));
}

TEST(PbrtMaterialMapping, DielectricSmoothRoughAndIndexMatched) {
  PbrtMaterialDesc d = of_kind(PbrtMaterialKind::Dielectric);
  d.eta = 1.33f;
  Material m = build_material(pbrt_material(d), pbrt_scene());
  ASSERT_TRUE(std::holds_alternative<Dielectric>(m.delta));
  EXPECT_EQ(std::get<Dielectric>(m.delta).eta, 1.33f);
  EXPECT_TRUE(m.oriented());
  d.uroughness = d.vroughness = 0.09f;
  m = build_material(pbrt_material(d), pbrt_scene());
  ASSERT_TRUE(std::holds_alternative<RoughDielectric>(m.surface));
  EXPECT_FALSE(m.has_delta());
  EXPECT_EQ(std::get<RoughDielectric>(m.surface).eta, 1.33f);
  EXPECT_FLOAT_EQ(std::get<RoughDielectric>(m.surface).distribution.alpha_x, 0.3f);
  EXPECT_TRUE(m.oriented());
  EXPECT_TRUE(m.has_surface_transmission());
  // eta = 1 is no interface, rough or not.
  d.eta = 1.0f;
  m = build_material(pbrt_material(d), pbrt_scene());
  ASSERT_TRUE(std::holds_alternative<Dielectric>(m.delta));
  EXPECT_FALSE(m.has_surface());
}

TEST(PbrtMaterialMapping, CoatedDiffuseCarriesEveryParameter) {
  PbrtMaterialDesc d = of_kind(PbrtMaterialKind::CoatedDiffuse);
  d.reflectance = Rgb(0.4f, 0.2f, 0.2f);
  d.uroughness = d.vroughness = 0.025f;
  d.eta = 1.6f;
  d.thickness = 0.05f;
  d.albedo = Rgb(0.3f, 1.5f, 0.0f);
  d.g = -0.3f;
  d.max_depth = 7;
  d.n_samples = 3;
  const Material m = build_material(pbrt_material(d), pbrt_scene());
  ASSERT_TRUE(std::holds_alternative<CoatedDiffuse>(m.surface));
  const CoatedDiffuse& c = std::get<CoatedDiffuse>(m.surface);
  EXPECT_EQ(c.base.reflectance, d.reflectance);
  EXPECT_EQ(c.layers.coat.eta, 1.6f);
  EXPECT_FLOAT_EQ(c.layers.coat.distribution.alpha_x, std::sqrt(0.025f));
  EXPECT_EQ(c.layers.thickness, 0.05f);
  EXPECT_EQ(c.layers.albedo, Rgb(0.3f, 1.0f, 0.0f));
  EXPECT_EQ(c.layers.g, -0.3f);
  EXPECT_EQ(c.layers.max_depth, 7);
  EXPECT_EQ(c.layers.n_samples, 3);
  EXPECT_EQ(c.layers.exit_weight, LayeredExitWeight::Consistent);
  EXPECT_FALSE(m.has_delta());
  EXPECT_FALSE(m.oriented());
  // pbrt's defaults: a smooth coat, whose mirror reflection is a specular lobe of the surface part.
  const Material def = build_material(pbrt_material(of_kind(PbrtMaterialKind::CoatedDiffuse)), pbrt_scene());
  EXPECT_TRUE(def.flags() & kLobeSpecular);
  EXPECT_TRUE(std::get<CoatedDiffuse>(def.surface).layers.coat.is_specular());
}

TEST(PbrtMaterialMapping, InterfacePassesThrough) {
  const Material m = build_material(pbrt_material(of_kind(PbrtMaterialKind::Interface)), pbrt_scene());
  EXPECT_TRUE(m.passes_through);
  EXPECT_FALSE(m.has_surface());
  // The fallback delta continues the ray unchanged with weight 1.
  const Vec3f wo = normalize(Vec3f(0.3f, -0.2f, 0.9f));
  const auto s = m.sample(wo, 0.5f, Vec2f(0.5f, 0.5f));
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->wi.x, -wo.x, 1e-6f);
  EXPECT_NEAR(s->wi.y, -wo.y, 1e-6f);
  EXPECT_NEAR(s->wi.z, -wo.z, 1e-6f);
  EXPECT_NEAR(s->f.r * std::abs(s->wi.z) / s->pdf, 1.0f, 1e-6f);
}

TEST(PbrtMaterialMapping, BadValuesNameFileMaterialAndType) {
  struct Case {
    PbrtMaterialDesc desc;
    std::string expected;
  };
  std::vector<Case> cases;
  auto add = [&](PbrtMaterialKind k, auto mutate, const std::string& expected) {
    PbrtMaterialDesc d = of_kind(k);
    mutate(d);
    cases.push_back({d, expected});
  };
  using K = PbrtMaterialKind;
  add(K::Diffuse, [](auto& d) { d.reflectance = Rgb(-0.1f, 0.5f, 0.5f); }, "pbrt diffuse material: reflectance");
  add(K::Diffuse, [](auto& d) { d.reflectance = Rgb(NAN, 0.5f, 0.5f); }, "reflectance must be finite");
  add(K::Conductor, [](auto& d) { d.uroughness = -0.1f; }, "pbrt conductor material: uroughness");
  add(K::Conductor, [](auto& d) { d.vroughness = INFINITY; }, "vroughness");
  add(K::Conductor, [](auto& d) { d.conductor_k = Rgb(1, -1, 1); }, "k must be finite and non-negative");
  add(K::Conductor, [](auto& d) { d.conductor_eta = Rgb(NAN); }, "eta must be finite");
  add(K::Conductor, [](auto& d) { d.conductor_reflectance = Rgb(-0.5f); }, "reflectance must be");
  add(K::Dielectric, [](auto& d) { d.eta = 0.0f; }, "pbrt dielectric material: eta must be a positive number");
  add(K::Dielectric, [](auto& d) { d.eta = -1.5f; }, "eta must be a positive number");
  add(K::CoatedDiffuse, [](auto& d) { d.thickness = -0.01f; }, "pbrt coateddiffuse material: thickness");
  add(K::CoatedDiffuse, [](auto& d) { d.g = 1.0f; }, "g must lie strictly between -1 and 1");
  add(K::CoatedDiffuse, [](auto& d) { d.n_samples = 0; }, "nsamples must be in [1, 1024]");
  add(K::CoatedDiffuse, [](auto& d) { d.n_samples = 100000; }, "nsamples must be in");
  add(K::CoatedDiffuse, [](auto& d) { d.max_depth = -1; }, "maxdepth must be in [0, 10000]");
  add(K::CoatedDiffuse, [](auto& d) { d.albedo = Rgb(0.5f, -1.0f, 0.5f); }, "albedo must be finite");
  add(K::CoatedDiffuse, [](auto& d) { d.eta = NAN; }, "eta must be a positive number");
  for (const Case& c : cases) {
    const std::string e = error_of(c.desc);
    EXPECT_NE(e.find("scene.pbrt"), std::string::npos) << e;
    EXPECT_NE(e.find("Material id=3"), std::string::npos) << e;
    EXPECT_NE(e.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in: " << e;
  }
}

}  // namespace
}  // namespace kiln
