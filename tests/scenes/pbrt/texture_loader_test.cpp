// pbrt-v4 Texture directives and textured material parameters (scenes/pbrt/textures.cpp, materials.cpp): every
// class with its parameters and pbrt-v4's defaults, the mappings, the imagemap options, the references from
// material parameters (constant textures folded, others kept), displacement and normal maps, and the errors for
// bad input (unknown class, missing file, a texture of the wrong kind), each naming the file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scenes/pbrt/loader.h"
#include "pbrt_test_util.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

// A folder with a scene file's neighbours: tex.png (a 1x1 PNG: only its existence matters to the loader).
std::string scene_dir() {
  const fs::path d = fs::path(KILN_TEST_TMP) / "pbrt_textures";
  fs::create_directories(d);
  std::ofstream(d / "tex.png", std::ios::binary) << "not read by the loader";
  std::ofstream(d / "height.exr", std::ios::binary) << "not read by the loader";
  return d.string();
}

SceneDesc parse(const std::string& world) { return parse_world(world, scene_dir()); }
std::string error_of(const std::string& world) { return world_error(world, scene_dir()); }

const PbrtTextureDesc& last_texture(const SceneDesc& s) { return s.pbrt_textures.back(); }

TEST(PbrtTextures, ConstantTexturesAreFoldedIntoTheParameter) {
  const SceneDesc s = parse(
      "Texture \"r\" \"spectrum\" \"constant\" \"rgb value\" [0.1 0.2 0.3]\n"
      "Texture \"k\" \"float\" \"constant\" \"float value\" 0.25\n"
      "Material \"conductor\" \"texture roughness\" \"k\" \"texture reflectance\" \"r\"\n"
      "Shape \"sphere\"\n");
  const PbrtMaterialDesc& m = *s.materials.back().pbrt;
  EXPECT_FALSE(m.conductor_reflectance.textured());
  EXPECT_EQ(m.conductor_reflectance.value, Rgb(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(m.uroughness, TexturedFloat(0.25f));
  EXPECT_EQ(m.vroughness, TexturedFloat(0.25f));
}

TEST(PbrtTextures, EveryTexturableParameterKeepsItsTexture) {
  const SceneDesc s = parse(
      "Texture \"c\" \"spectrum\" \"checkerboard\"\n"
      "Texture \"f\" \"float\" \"fbm\"\n"
      "Material \"coateddiffuse\" \"texture reflectance\" \"c\" \"texture albedo\" \"c\" \"texture roughness\" \"f\"\n"
      "  \"texture thickness\" \"f\" \"texture g\" \"f\"\n"
      "Shape \"sphere\"\n"
      "Material \"conductor\" \"texture eta\" \"c\" \"texture k\" \"c\" \"texture uroughness\" \"f\"\n"
      "Shape \"sphere\"\n"
      "Material \"dielectric\" \"texture eta\" \"f\" \"texture vroughness\" \"f\"\n"
      "Shape \"sphere\"\n");
  ASSERT_EQ(s.pbrt_textures.size(), 2u);
  const PbrtMaterialDesc& coat = *s.materials[0].pbrt;
  EXPECT_EQ(coat.reflectance.texture, 0);
  EXPECT_EQ(coat.albedo.texture, 0);
  EXPECT_EQ(coat.uroughness.texture, 1);
  EXPECT_EQ(coat.vroughness.texture, 1);
  EXPECT_EQ(coat.thickness.texture, 1);
  EXPECT_EQ(coat.g.texture, 1);
  const PbrtMaterialDesc& metal = *s.materials[1].pbrt;
  EXPECT_EQ(metal.conductor_eta.texture, 0);
  EXPECT_EQ(metal.conductor_k.texture, 0);
  EXPECT_EQ(metal.uroughness.texture, 1);
  EXPECT_FALSE(metal.vroughness.textured());
  const PbrtMaterialDesc& glass = *s.materials[2].pbrt;
  EXPECT_EQ(glass.eta.texture, 1);
  EXPECT_EQ(glass.vroughness.texture, 1);
}

// The materials with several layers or sides: every parameter pbrt-v4 lets a texture set keeps it, a mix's amount
// too (chosen on per hit, without a warning).
TEST(PbrtTextures, CoatedConductorDiffuseTransmissionAndThinDielectricKeepTheirTextures) {
  const SceneDesc s = parse(
      "Texture \"c\" \"spectrum\" \"checkerboard\"\n"
      "Texture \"f\" \"float\" \"fbm\"\n"
      "Material \"coatedconductor\" \"texture interface.roughness\" \"f\" \"texture conductor.vroughness\" \"f\"\n"
      "  \"texture conductor.eta\" \"c\" \"texture conductor.k\" \"c\" \"texture albedo\" \"c\" \"texture g\" \"f\"\n"
      "Shape \"sphere\"\n"
      "Material \"diffusetransmission\" \"texture reflectance\" \"c\" \"texture transmittance\" \"c\"\n"
      "Shape \"sphere\"\n"
      "Material \"thindielectric\" \"texture eta\" \"f\"\n"
      "Shape \"sphere\"\n"
      "MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n"
      "Material \"mix\" \"string materials\" [\"a\" \"a\"] \"texture amount\" \"f\"\n"
      "Shape \"sphere\"\n");
  const PbrtMaterialDesc& coat = *s.materials[0].pbrt;
  EXPECT_EQ(coat.uroughness.texture, 1);
  EXPECT_EQ(coat.vroughness.texture, 1);
  EXPECT_FALSE(coat.conductor_uroughness.textured());
  EXPECT_EQ(coat.conductor_vroughness.texture, 1);
  EXPECT_EQ(coat.conductor_eta.texture, 0);
  EXPECT_EQ(coat.conductor_k.texture, 0);
  EXPECT_EQ(coat.albedo.texture, 0);
  EXPECT_EQ(coat.g.texture, 1);
  const PbrtMaterialDesc& leaf = *s.materials[1].pbrt;
  EXPECT_EQ(leaf.reflectance.texture, 0);
  EXPECT_EQ(leaf.transmittance.texture, 0);
  EXPECT_EQ(s.materials[2].pbrt->eta.texture, 1);
  ASSERT_TRUE(s.materials.back().mix);
  EXPECT_EQ(s.materials.back().mix->amount.texture, 1);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_TRUE(s.unsupported.empty()) << s.unsupported.front();
}

TEST(PbrtTextures, ClassesReadTheirOperandsWithPbrtDefaults) {
  SceneDesc s = parse("Texture \"a\" \"float\" \"mix\"\n");
  const PbrtTextureDesc* t = &last_texture(s);
  EXPECT_EQ(t->cls, TextureClass::Mix);
  EXPECT_TRUE(t->is_float);
  EXPECT_EQ(t->operands[kTexOperandTex1].value, Rgb(0.0f));
  EXPECT_EQ(t->operands[kTexOperandTex2].value, Rgb(1.0f));
  EXPECT_EQ(t->operands[kTexOperandAmount].value, Rgb(0.5f));

  s = parse("Texture \"g\" \"float\" \"fbm\"\nTexture \"a\" \"spectrum\" \"mix\" \"rgb tex1\" [0.1 0.2 0.3]"
            " \"texture amount\" \"g\"\n");
  t = &last_texture(s);
  EXPECT_FALSE(t->is_float);
  EXPECT_EQ(t->operands[kTexOperandTex1].value, Rgb(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(t->operands[kTexOperandAmount].texture, 0);

  s = parse("Texture \"s\" \"spectrum\" \"scale\" \"rgb tex\" [0.5 0.5 0.5] \"float scale\" 3\n");
  EXPECT_EQ(last_texture(s).operands[kTexOperandTex].value, Rgb(0.5f));
  EXPECT_EQ(last_texture(s).operands[kTexOperandScale].value, Rgb(3.0f));

  s = parse("Texture \"c\" \"float\" \"checkerboard\" \"integer dimension\" 3\n");
  EXPECT_EQ(last_texture(s).dimension, 3);
  EXPECT_EQ(last_texture(s).operands[kTexOperandTex1].value, Rgb(1.0f));
  EXPECT_EQ(last_texture(s).operands[kTexOperandTex2].value, Rgb(0.0f));

  // dots as pbrt renders them: "outside" in the dots, "inside" around them.
  s = parse("Texture \"d\" \"spectrum\" \"dots\" \"rgb inside\" [1 0 0]\n");
  EXPECT_EQ(last_texture(s).operands[kTexOperandBackground].value, Rgb(1, 0, 0));
  EXPECT_EQ(last_texture(s).operands[kTexOperandDot].value, Rgb(0.0f));

  s = parse("Texture \"b\" \"float\" \"bilerp\" \"float v11\" 4\n");
  EXPECT_EQ(last_texture(s).operands[kTexOperandV00].value, Rgb(0.0f));
  EXPECT_EQ(last_texture(s).operands[kTexOperandV01].value, Rgb(1.0f));
  EXPECT_EQ(last_texture(s).operands[kTexOperandV10].value, Rgb(0.0f));
  EXPECT_EQ(last_texture(s).operands[kTexOperandV11].value, Rgb(4.0f));

  s = parse("Texture \"m\" \"spectrum\" \"marble\" \"float scale\" 2 \"integer octaves\" 5\n");
  EXPECT_EQ(last_texture(s).marble_scale, 2.0f);
  EXPECT_EQ(last_texture(s).octaves, 5);
  EXPECT_EQ(last_texture(s).variation, 0.2f);
  EXPECT_EQ(last_texture(s).roughness, 0.5f);

  // directionmix's "dir" is a vector in the space of the Texture directive.
  s = parse("Rotate 90 0 0 1\nTexture \"d\" \"float\" \"directionmix\" \"vector3 dir\" [2 0 0]\n");
  EXPECT_NEAR(last_texture(s).direction.x, 0.0f, 1e-6f);
  EXPECT_NEAR(last_texture(s).direction.y, 1.0f, 1e-6f);
}

TEST(PbrtTextures, MappingsReadTheirParameters) {
  SceneDesc s = parse("Texture \"c\" \"float\" \"checkerboard\" \"float uscale\" 4 \"float vscale\" 2"
                      " \"float udelta\" 0.5 \"float vdelta\" 0.25\n");
  TextureMappingDesc m = last_texture(s).mapping;
  EXPECT_EQ(m.kind, TextureMapping::Uv);
  EXPECT_EQ(m.su, 4.0f);
  EXPECT_EQ(m.sv, 2.0f);
  EXPECT_EQ(m.du, 0.5f);
  EXPECT_EQ(m.dv, 0.25f);
  s = parse("Translate 1 2 3\nTexture \"c\" \"float\" \"checkerboard\" \"string mapping\" \"planar\""
            " \"vector3 v1\" [0 1 0] \"vector3 v2\" [0 0 1] \"float udelta\" 1\n");
  m = last_texture(s).mapping;
  EXPECT_EQ(m.kind, TextureMapping::Planar);
  EXPECT_EQ(m.v1, Vec3f(0, 1, 0));
  EXPECT_EQ(m.v2, Vec3f(0, 0, 1));
  EXPECT_EQ(m.du, 1.0f);
  EXPECT_EQ(m.world_to_texture.point(Vec3f(1, 2, 3)), Vec3f(0.0f));
  s = parse("Texture \"c\" \"float\" \"dots\" \"string mapping\" \"spherical\"\n");
  EXPECT_EQ(last_texture(s).mapping.kind, TextureMapping::Spherical);
  s = parse("Texture \"c\" \"float\" \"dots\" \"string mapping\" \"cylindrical\"\n");
  EXPECT_EQ(last_texture(s).mapping.kind, TextureMapping::Cylindrical);
}

TEST(PbrtTextures, ImagemapOptionsAndTheirDefaults) {
  const std::string dir = scene_dir();
  SceneDesc s = parse("Texture \"i\" \"spectrum\" \"imagemap\" \"string filename\" \"tex.png\"\n");
  ImageTextureDesc im = last_texture(s).image;
  EXPECT_EQ(im.path, dir + "/tex.png");
  EXPECT_EQ(im.filter, ImageFilter::Bilinear);
  EXPECT_EQ(im.wrap, ImageWrap::Repeat);
  EXPECT_EQ(im.encoding, ImageEncoding::Srgb);  // pbrt-v4: PNGs default to sRGB
  EXPECT_EQ(im.scale, 1.0f);
  EXPECT_FALSE(im.invert);
  ASSERT_EQ(s.external_files.size(), 1u);
  EXPECT_EQ(s.external_files[0], dir + "/tex.png");

  s = parse("Texture \"i\" \"float\" \"imagemap\" \"string filename\" \"height.exr\"\n");
  EXPECT_EQ(last_texture(s).image.encoding, ImageEncoding::Linear);  // everything else linear

  s = parse("Texture \"i\" \"float\" \"imagemap\" \"string filename\" \"tex.png\" \"string filter\" \"ewa\""
            " \"string wrap\" \"octahedralsphere\" \"string encoding\" \"gamma 1.8\" \"float scale\" 2"
            " \"bool invert\" true\n");
  im = last_texture(s).image;
  EXPECT_EQ(im.filter, ImageFilter::Ewa);
  EXPECT_EQ(im.wrap, ImageWrap::OctahedralSphere);
  EXPECT_EQ(im.encoding, ImageEncoding::Gamma);
  EXPECT_EQ(im.gamma, 1.8f);
  EXPECT_EQ(im.scale, 2.0f);
  EXPECT_TRUE(im.invert);
  for (const char* f : {"point", "bilinear", "trilinear", "ewa"})
    EXPECT_EQ(error_of(std::string("Texture \"i\" \"float\" \"imagemap\" \"string filename\" \"tex.png\""
                                   " \"string filter\" \"") + f + "\"\n"), "");
  for (const char* w : {"repeat", "black", "clamp"})
    EXPECT_EQ(error_of(std::string("Texture \"i\" \"float\" \"imagemap\" \"string filename\" \"tex.png\""
                                   " \"string wrap\" \"") + w + "\"\n"), "");
}

TEST(PbrtTextures, DisplacementAndNormalMapsAreKept) {
  const std::string dir = scene_dir();
  const SceneDesc s = parse(
      "Texture \"h\" \"float\" \"imagemap\" \"string filename\" \"height.exr\"\n"
      "Texture \"bump\" \"float\" \"scale\" \"texture tex\" \"h\" \"float scale\" 0.05\n"
      "Material \"diffuse\" \"texture displacement\" \"bump\"\n"
      "Shape \"sphere\"\n"
      "Material \"conductor\" \"string normalmap\" \"tex.png\"\n"
      "Shape \"sphere\"\n");
  EXPECT_EQ(s.materials[0].pbrt->displacement, 1);
  const PbrtMaterialDesc& metal = *s.materials[1].pbrt;
  ASSERT_GE(metal.normal_map, 0);
  const PbrtTextureDesc& nm = s.pbrt_textures[size_t(metal.normal_map)];
  EXPECT_EQ(nm.cls, TextureClass::ImageMap);
  EXPECT_EQ(nm.image.path, dir + "/tex.png");
  EXPECT_EQ(nm.image.encoding, ImageEncoding::Linear);  // normal maps are not decoded
  EXPECT_EQ(s.external_files.size(), 2u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
  EXPECT_TRUE(s.unsupported.empty());
}

TEST(PbrtTextures, FloatAndSpectrumTexturesHaveSeparateNames) {
  const SceneDesc s = parse(
      "Texture \"t\" \"float\" \"constant\" \"float value\" 0.3\n"
      "Texture \"t\" \"spectrum\" \"constant\" \"rgb value\" [0.1 0.2 0.3]\n"
      "Material \"coateddiffuse\" \"texture roughness\" \"t\" \"texture reflectance\" \"t\"\n"
      "Shape \"sphere\"\n");
  EXPECT_EQ(s.materials[0].pbrt->uroughness.value, 0.3f);
  EXPECT_EQ(s.materials[0].pbrt->reflectance.value, Rgb(0.1f, 0.2f, 0.3f));
}

TEST(PbrtTextures, PtexIsWarnedAndItsParametersKeepTheirDefaults) {
  const SceneDesc s = parse(
      "Texture \"p\" \"spectrum\" \"ptex\" \"string filename\" \"x.ptx\"\n"
      "Material \"diffuse\" \"texture reflectance\" \"p\"\n"
      "Shape \"sphere\"\n");
  EXPECT_EQ(s.materials[0].pbrt->reflectance, TexturedRgb(Rgb(0.5f)));
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_NE(s.warnings[0].find("line 5 (Texture \"p\"): ptex textures are not rendered"), std::string::npos);
  EXPECT_NE(s.warnings[1].find("line 6 (Material \"diffuse\"): \"reflectance\" uses texture \"p\""), std::string::npos);
}

TEST(PbrtTextures, BadInputNamesFileAndLine) {
  const struct {
    const char* world;
    const char* message;
  } cases[] = {
      {"Texture \"a\" \"spectrum\" \"plaid\"\n", "line 5 (Texture \"a\"): unknown texture class \"plaid\""},
      {"Texture \"a\" \"color\" \"constant\"\n", "line 5 (Texture \"a\"): texture type must be \"float\" or"},
      {"Texture \"a\" \"spectrum\" \"imagemap\" \"string filename\" \"missing.png\"\n",
       "line 5 (Texture \"a\"): cannot find \"missing.png\""},
      {"Texture \"a\" \"spectrum\" \"imagemap\"\n", "line 5 (Texture \"a\"): an imagemap needs \"string filename\""},
      {"Texture \"a\" \"spectrum\" \"fbm\"\n", "line 5 (Texture \"a\"): texture class \"fbm\" has no spectrum textures"},
      {"Texture \"a\" \"float\" \"marble\"\n", "line 5 (Texture \"a\"): texture class \"marble\" has no float textures"},
      {"Texture \"a\" \"float\" \"constant\"\nTexture \"a\" \"float\" \"constant\"\n",
       "line 6 (Texture \"a\"): float texture \"a\" is defined twice"},
      {"Texture \"s\" \"spectrum\" \"checkerboard\"\nMaterial \"diffuse\" \"texture displacement\" \"s\"\n",
       "line 6 (Material \"diffuse\"): \"displacement\" needs a float texture, but \"s\" is a spectrum texture"},
      {"Material \"diffuse\" \"texture reflectance\" \"nope\"\n",
       "line 5 (Material \"diffuse\"): \"reflectance\": no spectrum texture named \"nope\""},
      {"Texture \"f\" \"float\" \"checkerboard\"\nTexture \"m\" \"float\" \"mix\" \"texture tex1\" \"g\"\n",
       "line 6 (Texture \"m\"): \"tex1\": no float texture named \"g\""},
      {"Texture \"a\" \"float\" \"checkerboard\" \"string mapping\" \"cubic\"\n", "unknown \"mapping\" \"cubic\""},
      {"Texture \"a\" \"float\" \"checkerboard\" \"integer dimension\" 4\n", "\"dimension\" must be 2 or 3"},
      {"Texture \"a\" \"float\" \"imagemap\" \"string filename\" \"tex.png\" \"string wrap\" \"mirror\"\n",
       "unknown \"wrap\" \"mirror\""},
      {"Texture \"a\" \"float\" \"imagemap\" \"string filename\" \"tex.png\" \"string filter\" \"box\"\n",
       "unknown \"filter\" \"box\""},
      {"Texture \"a\" \"float\" \"imagemap\" \"string filename\" \"tex.png\" \"string encoding\" \"gamma -1\"\n",
       "the gamma must be a positive number"},
      {"Texture \"a\" \"float\" \"imagemap\" \"string filename\" \"tex.png\" \"string encoding\" \"log\"\n",
       "unknown \"encoding\" \"log\""},
      {"Material \"diffuse\" \"string normalmap\" \"missing.png\"\n", "line 5 (Material \"diffuse\"): cannot find"},
  };
  for (const auto& c : cases) {
    const std::string e = error_of(c.world);
    EXPECT_NE(e.find("scene.pbrt: "), std::string::npos) << c.world << " -> " << e;
    EXPECT_NE(e.find(c.message), std::string::npos) << c.world << " -> " << e;
  }
}

}  // namespace
}  // namespace kiln
