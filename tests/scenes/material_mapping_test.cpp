// scenes/material_mapping: CENG795 / CS171 material descriptions -> Kiln materials, and the errors for bad input.
#include "scenes/material_mapping.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>

#include "core/error.h"
#include "scenes/loader.h"
#include "support/shared_data.h"

namespace kiln {
namespace {

SceneDesc scene_with_brdf(BrdfDesc b) {
  SceneDesc s;
  s.source_path = "test.xml";
  s.brdfs.push_back(b);
  return s;
}

MaterialDesc plain(Rgb kd, Rgb ks) {
  MaterialDesc m;
  m.id = 7;
  m.diffuse = kd;
  m.specular = ks;
  return m;
}

std::string error_of(const MaterialDesc& m, const SceneDesc& s) {
  try {
    build_material(m, s);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(MaterialMapping, NoBrdfIsClassicOriginalBlinnPhong) {
  MaterialDesc m = plain(Rgb(0.1f, 0.2f, 0.3f), Rgb(0.5f));
  m.phong_exponent = 300;
  m.ambient = Rgb(0.4f);
  const Material mat = build_material(m, SceneDesc{});
  ASSERT_TRUE(std::holds_alternative<BlinnPhong>(mat.surface));
  const auto& b = std::get<BlinnPhong>(mat.surface);
  EXPECT_EQ(b.variant, PhongVariant::Original);
  EXPECT_EQ(b.exponent, 300.0f);
  EXPECT_EQ(b.kd, Rgb(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(b.ks, Rgb(0.5f));
  EXPECT_EQ(mat.ambient, Rgb(0.4f));
  EXPECT_FALSE(mat.has_delta());
  // Classic shading: L = [kd cos + ks cos^p(alpha_h)] E, i.e. f cos with f = kd + ks cos^p / cos.
  const Vec3f wo(0, 0, 1), wi(0.6f, 0.0f, 0.8f);
  const float cos_h = normalize(wo + wi).z;
  EXPECT_NEAR(mat.eval(wo, wi).r * wi.z, 0.1f * wi.z + 0.5f * std::pow(cos_h, 300.0f), 1e-6f);
}

TEST(MaterialMapping, BrdfKindsAndVariants) {
  struct Case {
    BrdfKind kind;
    bool normalized;
    bool phong;
    PhongVariant variant;
  };
  const Case cases[] = {
      {BrdfKind::OriginalPhong, false, true, PhongVariant::Original},
      {BrdfKind::ModifiedPhong, false, true, PhongVariant::Modified},
      {BrdfKind::ModifiedPhong, true, true, PhongVariant::ModifiedNormalized},
      {BrdfKind::OriginalBlinnPhong, false, false, PhongVariant::Original},
      {BrdfKind::ModifiedBlinnPhong, false, false, PhongVariant::Modified},
      {BrdfKind::ModifiedBlinnPhong, true, false, PhongVariant::ModifiedNormalized},
  };
  for (const Case& c : cases) {
    BrdfDesc b;
    b.kind = c.kind;
    b.normalized = c.normalized;
    b.exponent = 50;
    MaterialDesc m = plain(Rgb(0.2f), Rgb(0.7f));
    m.brdf = 0;
    m.phong_exponent = 3;  // ignored when a BRDF is given
    const Material mat = build_material(m, scene_with_brdf(b));
    if (c.phong) {
      ASSERT_TRUE(std::holds_alternative<Phong>(mat.surface));
      EXPECT_EQ(std::get<Phong>(mat.surface).variant, c.variant);
      EXPECT_EQ(std::get<Phong>(mat.surface).exponent, 50.0f);
    } else {
      ASSERT_TRUE(std::holds_alternative<BlinnPhong>(mat.surface));
      EXPECT_EQ(std::get<BlinnPhong>(mat.surface).variant, c.variant);
      EXPECT_EQ(std::get<BlinnPhong>(mat.surface).exponent, 50.0f);
    }
  }
}

// A lobe whose reflectance is zero is left out: a Phong / Blinn-Phong form or Torrance-Sparrow without ks compiles to
// the Lambertian with the same f and the same sampling pdf at every pair of directions (so the same estimator).
TEST(MaterialMapping, ZeroSpecularLobeCompilesToLambert) {
  const Rgb kd(0.3f, 0.2f, 0.1f);
  struct Case {
    const char* name;
    std::optional<BrdfKind> kind;  // none: the classic course shading
    bool normalized;
    SurfaceBrdf uncompiled;
  };
  const Case cases[] = {
      {"classic", std::nullopt, false, BlinnPhong{kd, Rgb(0), 30, PhongVariant::Original}},
      {"phong original", BrdfKind::OriginalPhong, false, Phong{kd, Rgb(0), 30, PhongVariant::Original}},
      {"phong modified", BrdfKind::ModifiedPhong, false, Phong{kd, Rgb(0), 30, PhongVariant::Modified}},
      {"phong normalized", BrdfKind::ModifiedPhong, true, Phong{kd, Rgb(0), 30, PhongVariant::ModifiedNormalized}},
      {"blinn original", BrdfKind::OriginalBlinnPhong, false, BlinnPhong{kd, Rgb(0), 30, PhongVariant::Original}},
      {"blinn modified", BrdfKind::ModifiedBlinnPhong, false, BlinnPhong{kd, Rgb(0), 30, PhongVariant::Modified}},
      {"blinn normalized", BrdfKind::ModifiedBlinnPhong, true,
       BlinnPhong{kd, Rgb(0), 30, PhongVariant::ModifiedNormalized}},
      {"torrance-sparrow", BrdfKind::TorranceSparrow, false, TorranceSparrow{kd, Rgb(0), 30, 1.5f, 0.0f, false}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    MaterialDesc m = plain(kd, Rgb(0));
    m.phong_exponent = 30;
    m.has_refraction_index = true;
    m.refraction_index = 1.5f;
    SceneDesc scene;
    if (c.kind) {
      BrdfDesc b;
      b.kind = *c.kind;
      b.normalized = c.normalized;
      b.exponent = 30;
      scene = scene_with_brdf(b);
      m.brdf = 0;
    }
    const Material compiled = build_material(m, scene);
    ASSERT_TRUE(std::holds_alternative<Lambert>(compiled.surface));
    EXPECT_EQ(compiled.describe(), "lambert");
    Material reference;
    reference.surface = c.uncompiled;
    uint64_t state = 0x9e3779b97f4a7c15ull;
    auto next = [&state] {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      return float(state >> 40) * 0x1p-24f;
    };
    auto direction = [&] {
      const float z = next(), phi = 6.2831853f * next(), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      return Vec3f(r * std::cos(phi), r * std::sin(phi), z);
    };
    for (int i = 0; i < 1000; ++i) {
      const Vec3f wo = direction(), wi = direction();
      const Rgb a = compiled.eval(wo, wi), b = reference.eval(wo, wi);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-6f * b[k] + 1e-12f) << "channel " << k;
      EXPECT_NEAR(compiled.pdf(wo, wi), reference.pdf(wo, wi), 1e-6f * reference.pdf(wo, wi) + 1e-12f);
    }
  }
  // Torrance-Sparrow with kdfresnel weights its diffuse term by 1 - F(wo, wi): not a Lambertian, kept.
  BrdfDesc ts;
  ts.kind = BrdfKind::TorranceSparrow;
  ts.kd_fresnel = true;
  MaterialDesc m = plain(kd, Rgb(0));
  m.brdf = 0;
  m.has_refraction_index = true;
  m.refraction_index = 1.5f;
  EXPECT_TRUE(std::holds_alternative<TorranceSparrow>(build_material(m, scene_with_brdf(ts)).surface));
  // A non-zero specular lobe is kept.
  m.specular = Rgb(0.1f);
  EXPECT_TRUE(std::holds_alternative<TorranceSparrow>(build_material(m, scene_with_brdf(ts)).surface));
}

TEST(MaterialMapping, TorranceSparrowIndexSources) {
  BrdfDesc b;
  b.kind = BrdfKind::TorranceSparrow;
  b.exponent = 50;
  // 2019: the BRDF's RefractiveIndex child.
  b.refractive_index = 0.37f;
  MaterialDesc m = plain(Rgb(0), Rgb(1.0f, 0.86f, 0.57f));
  m.brdf = 0;
  auto ts = std::get<TorranceSparrow>(build_material(m, scene_with_brdf(b)).surface);
  EXPECT_EQ(ts.eta, 0.37f);
  EXPECT_EQ(ts.kappa, 0.0f);
  EXPECT_FALSE(ts.kd_fresnel);
  EXPECT_NEAR(ts.r0(), std::pow(0.63f / 1.37f, 2.0f), 1e-6f);
  // 2021: the material's RefractionIndex / AbsorptionIndex, kdfresnel attribute.
  b.refractive_index.reset();
  b.kd_fresnel = true;
  m.diffuse = Rgb(0.5f, 0.43f, 0.285f);
  m.refraction_index = 0.37f;
  m.has_refraction_index = true;
  m.absorption_index = 2.82f;
  ts = std::get<TorranceSparrow>(build_material(m, scene_with_brdf(b)).surface);
  EXPECT_EQ(ts.eta, 0.37f);
  EXPECT_EQ(ts.kappa, 2.82f);
  EXPECT_TRUE(ts.kd_fresnel);
  EXPECT_EQ(ts.kd, Rgb(0.5f, 0.43f, 0.285f));
}

TEST(MaterialMapping, LambertBrdfIsKdOverPi) {
  BrdfDesc b;
  b.kind = BrdfKind::Lambert;
  MaterialDesc m = plain(Rgb(0.725f, 0.71f, 0.68f), Rgb(0));
  m.brdf = 0;
  const Material mat = build_material(m, scene_with_brdf(b));
  ASSERT_TRUE(std::holds_alternative<Lambert>(mat.surface));
  EXPECT_NEAR(mat.eval(Vec3f(0, 0, 1), normalize(Vec3f(1, 0, 1))).r, 0.725f / 3.14159265f, 1e-6f);
}

TEST(MaterialMapping, BlackSurfaceIsDropped) {
  MaterialDesc m = plain(Rgb(0), Rgb(0));
  m.mirror = Rgb(0.9f);
  const Material mat = build_material(m, SceneDesc{});
  EXPECT_FALSE(mat.has_surface());
  ASSERT_TRUE(std::holds_alternative<Mirror>(mat.delta));
  EXPECT_EQ(std::get<Mirror>(mat.delta).reflectance, Rgb(0.9f));
}

TEST(MaterialMapping, Year2019DeltaInference) {
  // Non-zero Transparency: dielectric with per-unit-length transmittance a, absorption -ln(a).
  MaterialDesc glass = plain(Rgb(0), Rgb(0.3f));
  glass.transparency = Rgb(0.99f, 0.5f, 1.0f);
  glass.refraction_index = 2.0f;
  glass.has_refraction_index = true;
  glass.mirror = Rgb(0.5f);  // a dielectric already reflects: Transparency wins
  const Material g = build_material(glass, SceneDesc{});
  ASSERT_TRUE(std::holds_alternative<Dielectric>(g.delta));
  EXPECT_EQ(std::get<Dielectric>(g.delta).eta, 2.0f);
  EXPECT_NEAR(g.transmittance(2.0f).r, 0.99f * 0.99f, 1e-6f);
  EXPECT_NEAR(g.transmittance(2.0f).g, 0.25f, 1e-6f);
  EXPECT_EQ(g.transmittance(2.0f).b, 1.0f);
  EXPECT_TRUE(g.has_surface());  // the glass keeps its specular highlight
  // A zero channel stays finite: no NaN even at distance 0.
  glass.transparency = Rgb(0.0f, 1.0f, 1.0f);
  const Material opaque_red = build_material(glass, SceneDesc{});
  EXPECT_TRUE(opaque_red.transmittance(0.0f).is_finite());
  EXPECT_EQ(opaque_red.transmittance(0.0f).r, 1.0f);
  EXPECT_LT(opaque_red.transmittance(10.0f).r, 1e-30f);
  // Non-zero MirrorReflectance with roughness: a (glossy) mirror on top of the surface.
  MaterialDesc metal = plain(Rgb(0.23f), Rgb(0.23f));
  metal.mirror = Rgb(0.77f);
  metal.roughness = 0.1f;
  const Material mm = build_material(metal, SceneDesc{});
  ASSERT_TRUE(std::holds_alternative<Mirror>(mm.delta));
  EXPECT_EQ(mm.roughness, 0.1f);
  EXPECT_TRUE(mm.has_surface());
  // All zero: plain surface.
  EXPECT_FALSE(build_material(plain(Rgb(0.5f), Rgb(0)), SceneDesc{}).has_delta());
}

TEST(MaterialMapping, Year2021Types) {
  MaterialDesc mirror = plain(Rgb(0), Rgb(0));
  mirror.type = MaterialType::Mirror;
  mirror.mirror = Rgb(0.8f);
  EXPECT_TRUE(std::holds_alternative<Mirror>(build_material(mirror, SceneDesc{}).delta));

  MaterialDesc conductor = plain(Rgb(0), Rgb(0));
  conductor.type = MaterialType::Conductor;
  conductor.mirror = Rgb(1.0f, 0.86f, 0.57f);
  conductor.refraction_index = 0.37f;
  conductor.has_refraction_index = true;
  conductor.absorption_index = 2.82f;
  const Material c = build_material(conductor, SceneDesc{});
  ASSERT_TRUE(std::holds_alternative<Conductor>(c.delta));
  EXPECT_EQ(std::get<Conductor>(c.delta).eta, 0.37f);
  EXPECT_EQ(std::get<Conductor>(c.delta).kappa, 2.82f);
  EXPECT_EQ(std::get<Conductor>(c.delta).reflectance, Rgb(1.0f, 0.86f, 0.57f));

  MaterialDesc dielectric = plain(Rgb(0), Rgb(0));
  dielectric.type = MaterialType::Dielectric;
  dielectric.refraction_index = 1.55f;
  dielectric.has_refraction_index = true;
  dielectric.absorption_coefficient = Rgb(0.01f);
  const Material d = build_material(dielectric, SceneDesc{});
  ASSERT_TRUE(std::holds_alternative<Dielectric>(d.delta));
  EXPECT_EQ(std::get<Dielectric>(d.delta).eta, 1.55f);
  EXPECT_EQ(d.absorption, Rgb(0.01f));
  EXPECT_FALSE(d.has_surface());
}

TEST(MaterialMapping, DegammaDecodesColours) {
  MaterialDesc m = plain(Rgb(0.651f, 0.389f, 0.389f), Rgb(0.5f));
  m.ambient = Rgb(0.651f, 0.389f, 0.389f);
  m.mirror = Rgb(0.25f);
  m.degamma = true;
  const Material mat = build_material(m, SceneDesc{});
  const auto& b = std::get<BlinnPhong>(mat.surface);
  EXPECT_NEAR(b.kd.r, std::pow(0.651f, 2.2f), 1e-6f);
  EXPECT_NEAR(b.ks.r, std::pow(0.5f, 2.2f), 1e-6f);
  EXPECT_NEAR(mat.ambient.g, std::pow(0.389f, 2.2f), 1e-6f);
  EXPECT_NEAR(std::get<Mirror>(mat.delta).reflectance.r, std::pow(0.25f, 2.2f), 1e-6f);
}

TEST(MaterialMapping, BadInputNamesFileAndMaterial) {
  MaterialDesc m = plain(Rgb(0.5f), Rgb(0.5f));
  m.brdf = 3;
  SceneDesc s;
  s.source_path = "scene.xml";
  std::string e = error_of(m, s);
  EXPECT_NE(e.find("scene.xml"), std::string::npos) << e;
  EXPECT_NE(e.find("Material id=7"), std::string::npos) << e;
  EXPECT_NE(e.find("BRDF index 3"), std::string::npos) << e;

  MaterialDesc d = plain(Rgb(0), Rgb(0));
  d.type = MaterialType::Dielectric;
  e = error_of(d, s);
  EXPECT_NE(e.find("RefractionIndex"), std::string::npos) << e;
  d.has_refraction_index = true;
  d.refraction_index = -1.0f;
  EXPECT_NE(error_of(d, s).find("positive"), std::string::npos);

  BrdfDesc ts;
  ts.kind = BrdfKind::TorranceSparrow;
  MaterialDesc t = plain(Rgb(0), Rgb(1));
  t.brdf = 0;
  EXPECT_NE(error_of(t, scene_with_brdf(ts)).find("RefractionIndex"), std::string::npos);

  BrdfDesc negative;
  negative.exponent = -2;
  MaterialDesc n = plain(Rgb(0.5f), Rgb(0));
  n.brdf = 0;
  EXPECT_NE(error_of(n, scene_with_brdf(negative)).find("Exponent"), std::string::npos);

  MaterialDesc neg = plain(Rgb(-0.1f), Rgb(0));
  EXPECT_NE(error_of(neg, s).find("DiffuseReflectance"), std::string::npos);
  MaterialDesc rough = plain(Rgb(0.5f), Rgb(0));
  rough.roughness = std::nanf("");
  EXPECT_NE(error_of(rough, s).find("Roughness"), std::string::npos);
}

// ---- The staged course scenes (integration with the loaders) ----

const std::filesystem::path kShared = KILN_SHARED_DIR;

std::vector<Material> load_materials(const std::string& rel) {
  const SceneDesc s = load_scene((kShared / "scenes" / rel).string());
  std::vector<Material> out;
  for (const MaterialDesc& m : s.materials) out.push_back(build_material(m, s));
  return out;
}

#define REQUIRE_SHARED() KILN_NEED_SHARED_PATH(kShared / "scenes")

TEST(MaterialMappingScenes, BrdfFolderMapsEveryKind) {
  REQUIRE_SHARED();
  for (const char* folder : {"ceng795/brdf/", "ceng795/brdf_2021/"})
    for (const char* name :
         {"brdf_phong_original", "brdf_phong_modified", "brdf_phong_modified_normalized", "brdf_blinnphong_original",
          "brdf_blinnphong_modified", "brdf_blinnphong_modified_normalized", "brdf_torrancesparrow"}) {
      SCOPED_TRACE(std::string(folder) + name);
      const auto mats = load_materials(std::string(folder) + name + ".xml");
      ASSERT_EQ(mats.size(), 1u);
      const std::string n = name;
      if (n.find("torrance") != std::string::npos) {
        ASSERT_TRUE(std::holds_alternative<TorranceSparrow>(mats[0].surface));
        EXPECT_EQ(std::get<TorranceSparrow>(mats[0].surface).eta, 0.37f);
        EXPECT_EQ(std::get<TorranceSparrow>(mats[0].surface).exponent, 50.0f);
      } else if (n.find("blinn") != std::string::npos) {
        ASSERT_TRUE(std::holds_alternative<BlinnPhong>(mats[0].surface));
        EXPECT_EQ(std::get<BlinnPhong>(mats[0].surface).exponent, 50.0f);
      } else {
        ASSERT_TRUE(std::holds_alternative<Phong>(mats[0].surface));
      }
    }
}

TEST(MaterialMappingScenes, CornellboxRecursive2021) {
  REQUIRE_SHARED();
  const auto mats = load_materials("ceng795/regression/hw1_2021/cornellbox_recursive.xml");
  ASSERT_EQ(mats.size(), 6u);
  EXPECT_EQ(std::get<BlinnPhong>(mats[3].surface).exponent, 300.0f);
  ASSERT_TRUE(std::holds_alternative<Conductor>(mats[4].delta));
  EXPECT_FALSE(mats[4].has_surface());
  ASSERT_TRUE(std::holds_alternative<Dielectric>(mats[5].delta));
  EXPECT_EQ(std::get<Dielectric>(mats[5].delta).eta, 1.55f);
  EXPECT_EQ(mats[5].absorption, Rgb(0.01f));
}

TEST(MaterialMappingScenes, PathTracingGlass2019) {
  REQUIRE_SHARED();
  const auto mats = load_materials("ceng795/pathTracing/cornellbox_jaroslav_path_glass.xml");
  ASSERT_EQ(mats.size(), 8u);
  EXPECT_FALSE(mats[0].has_surface());  // the light's all-zero material
  EXPECT_FALSE(mats[0].has_delta());
  // Its diffuse walls are normalized Phong without a specular lobe: compiled to Lambert(kd).
  ASSERT_TRUE(std::holds_alternative<Lambert>(mats[1].surface));
  EXPECT_EQ(std::get<Lambert>(mats[1].surface).reflectance, Rgb(0.803922f));
  ASSERT_TRUE(std::holds_alternative<Dielectric>(mats[6].delta));
  EXPECT_EQ(std::get<Dielectric>(mats[6].delta).eta, 2.0f);
  EXPECT_NEAR(mats[6].transmittance(1.0f).r, 0.99f, 1e-6f);
  ASSERT_TRUE(std::holds_alternative<Mirror>(mats[7].delta));
  EXPECT_FALSE(mats[7].has_surface());
}

TEST(MaterialMappingScenes, EveryStagedSceneBuilds) {
  REQUIRE_SHARED();
  for (const char* rel : {"ceng795/regression/hw3_2019/metal_glass_plates.xml",
                          "ceng795/regression/hw5_2019/cube_point_hdr.xml", "ceng795/regression/hw1_2021/spheres.xml",
                          "ceng795/directLighting/cornellbox_jaroslav_glossy.xml", "cs171/configs/simple.json"}) {
    SCOPED_TRACE(rel);
    EXPECT_NO_THROW(load_materials(rel));
  }
  const auto plates = load_materials("ceng795/regression/hw3_2019/metal_glass_plates.xml");
  ASSERT_TRUE(std::holds_alternative<Mirror>(plates[3].delta));
  EXPECT_EQ(plates[3].roughness, 0.1f);
  ASSERT_TRUE(std::holds_alternative<Dielectric>(plates[2].delta));
  const auto cs = load_materials("cs171/configs/simple.json");
  for (const Material& m : cs) {
    if (m.has_surface()) {
      EXPECT_TRUE(std::holds_alternative<Lambert>(m.surface));
    }
  }
}

}  // namespace
}  // namespace kiln
