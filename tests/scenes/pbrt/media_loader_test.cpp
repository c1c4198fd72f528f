// pbrt-v4 media: MakeNamedMedium parameters into SceneDesc::media, MediumInterface on shapes (with pbrt's sides, and
// forward references resolved when the file ends), the camera's medium, and every malformed medium an error naming
// file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "media/emission_table.h"
#include "scenes/pbrt/loader.h"
#include "support/nanovdb_file.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

// The options block ends on line 4 (MediumInterface before Camera gives the camera its medium); the world starts
// on line 6.
std::string head(const std::string& camera_medium = "") {
  return "LookAt 0 0 5  0 0 0  0 1 0\n" +
         (camera_medium.empty() ? std::string("\n") : "MediumInterface \"\" \"" + camera_medium + "\"\n") +
         "Camera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n";
}

std::string tmp(const std::string& name) {
  const fs::path d = fs::path(KILN_TEST_TMP) / "pbrt_media";
  fs::create_directories(d);
  return (d / name).string();
}

std::string error_of(const std::string& text, const std::string& path = "media.pbrt") {
  try {
    parse_pbrt(text, path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kFog =
    "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.1 0.2 0.4] \"rgb sigma_s\" [1 2 3]"
    " \"float scale\" 2 \"float g\" 0.5 \"rgb Le\" [1 0.5 0] \"float Lescale\" 3\n";

TEST(PbrtMedia, HomogeneousParametersAreScaled) {
  const SceneDesc s = parse_pbrt(head() + kFog, "media.pbrt");
  ASSERT_EQ(s.media.size(), 1u);
  const MediumDesc& m = s.media[0];
  EXPECT_EQ(m.name, "fog");
  EXPECT_NE(m.element.find("media.pbrt: line 6 (MakeNamedMedium \"fog\")"), std::string::npos) << m.element;
  EXPECT_FLOAT_EQ(m.g, 0.5f);
  const auto& h = std::get<HomogeneousMediumDesc>(m.params);
  EXPECT_EQ(h.sigma_a, Rgb(0.2f, 0.4f, 0.8f));
  EXPECT_EQ(h.sigma_s, Rgb(2.0f, 4.0f, 6.0f));
  EXPECT_EQ(h.le, Rgb(3.0f, 1.5f, 0.0f));
  EXPECT_TRUE(m.blackbody.empty()) << "no temperature grid, no emission table";
}

TEST(PbrtMedia, PresetsAreMeasuredMediaAndGIsClampedLikePbrt) {
  const SceneDesc s = parse_pbrt(head() +
                                     "MakeNamedMedium \"milk\" \"string type\" \"homogeneous\" \"string preset\" "
                                     "\"Wholemilk\" \"float scale\" 10 \"float g\" 1\n",
                                 "media.pbrt");
  const auto& h = std::get<HomogeneousMediumDesc>(s.media[0].params);
  EXPECT_NEAR(h.sigma_s.r, 25.5f, 1e-4f);  // 2.55 per mm (Jensen et al. 2001) times the scale
  EXPECT_NEAR(h.sigma_a.b, 0.14f, 1e-5f);
  EXPECT_FLOAT_EQ(s.media[0].g, 0.99f);
  const SceneDesc unknown =
      parse_pbrt(head() + "MakeNamedMedium \"x\" \"string type\" \"homogeneous\" \"string preset\" \"Lava\"\n", "m.pbrt");
  ASSERT_EQ(unknown.warnings.size(), 1u);
  EXPECT_NE(unknown.warnings[0].find("no measured medium named \"Lava\""), std::string::npos);
}

TEST(PbrtMedia, UniformGridAndRgbGrid) {
  const SceneDesc s = parse_pbrt(head() +
                                     "Translate 1 2 3\n"
                                     "MakeNamedMedium \"smoke\" \"string type\" \"uniformgrid\" \"integer nx\" 2 "
                                     "\"integer ny\" 1 \"integer nz\" 2 \"float density\" [0 1 2 3] \"point3 p0\" [-1 -1 "
                                     "-1] \"point3 p1\" [1 1 1] \"rgb sigma_s\" [1 1 1] \"float scale\" 0.5\n"
                                     "MakeNamedMedium \"tint\" \"string type\" \"rgbgrid\" \"rgb sigma_a\" [1 0 0  0 1 0]"
                                     " \"integer nx\" 2\n",
                                 "media.pbrt");
  ASSERT_EQ(s.media.size(), 2u);
  const auto& g = std::get<GridMediumDesc>(s.media[0].params);
  EXPECT_EQ(g.lattice.count(), 4u);
  EXPECT_EQ(g.density[3], 3.0f);
  EXPECT_EQ(g.sigma_s, Rgb(0.5f));
  EXPECT_EQ(g.sigma_a, Rgb(0.5f)) << "pbrt's default sigma_a is 1";
  EXPECT_EQ(g.le_scale, std::vector<float>{1.0f});
  EXPECT_EQ(s.media[0].to_world.point(Vec3f(0.0f)), Vec3f(1, 2, 3)) << "the medium's space is the CTM's";
  const auto& rgb = std::get<RgbGridMediumDesc>(s.media[1].params);
  EXPECT_EQ(rgb.sigma_a.size(), 2u);
  EXPECT_TRUE(rgb.sigma_s.empty());
}

TEST(PbrtMedia, TemperatureGridsGetABlackbodyTable) {
  const SceneDesc s = parse_pbrt(head() +
                                     "MakeNamedMedium \"fire\" \"string type\" \"uniformgrid\" \"float density\" [1] "
                                     "\"float temperature\" [1500] \"float temperaturecutoff\" 100 "
                                     "\"float temperaturescale\" 2\n",
                                 "media.pbrt");
  const MediumDesc& m = s.media[0];
  ASSERT_EQ(m.blackbody.size(), size_t(kEmissionTableSize));
  const auto& g = std::get<GridMediumDesc>(m.params);
  EXPECT_EQ(g.temperature_offset, 100.0f);
  EXPECT_EQ(g.temperature_scale, 2.0f);
  // pbrt-v4's blackbody is normalised to 1 at its peak: a hotter body is brighter, and red at 1500 K.
  const Rgb warm = emission_at(m.blackbody, 1500.0f), hot = emission_at(m.blackbody, 6000.0f);
  EXPECT_GT(warm.r, 2.0f * warm.b);
  EXPECT_GT(hot.luminance(), 5.0f * warm.luminance());
  EXPECT_EQ(emission_at(m.blackbody, 90.0f), Rgb(0.0f)) << "pbrt-v4 leaves 100 K and below dark";
}

TEST(PbrtMedia, MediumInterfaceSidesAndForwardReferences) {
  // The camera names "fog" before it is defined (pbrt-v4 allows it); the sphere is turned inside out by
  // ReverseOrientation, so its "inside" medium is around it; an unnamed side is vacuum.
  const SceneDesc s = parse_pbrt(head("fog") + kFog +
                                     "MakeNamedMedium \"dust\" \"string type\" \"homogeneous\"\n"
                                     "AttributeBegin\nMediumInterface \"fog\" \"\"\nMaterial \"interface\"\n"
                                     "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n"
                                     "ReverseOrientation\nShape \"sphere\"\nAttributeEnd\n"
                                     "MediumInterface \"dust\"\nShape \"sphere\"\n",
                                 "media.pbrt");
  ASSERT_EQ(s.cameras[0].medium, 0);
  EXPECT_EQ(s.meshes[0].media, (MediumInterfaceDesc{0, -1}));
  EXPECT_EQ(s.spheres[0].media, (MediumInterfaceDesc{-1, 0}));
  EXPECT_EQ(s.spheres[1].media, (MediumInterfaceDesc{1, 1})) << "one name: both sides, no transition";
}

TEST(PbrtMedia, NanoVdbFileIsResolvedAndListedAsExternal) {
  test::NanoVdbLattice l;
  l.values = {1, 2, 3, 4, 5, 6, 7, 8};
  l.nx = l.ny = l.nz = 2;
  test::write_nanovdb(tmp("cloud.nvdb"), {l});
  const SceneDesc s = parse_pbrt(head() +
                                     "MakeNamedMedium \"c\" \"string type\" \"nanovdb\" \"string filename\" "
                                     "\"cloud.nvdb\" \"spectrum sigma_s\" [200 10 900 10] \"float Lescale\" 2\n",
                                 tmp("scene.pbrt"));
  const auto& v = std::get<NanoVdbMediumDesc>(s.media[0].params);
  EXPECT_EQ(fs::path(v.path), fs::path(tmp("cloud.nvdb")).lexically_normal());
  EXPECT_EQ(v.sigma_s, Rgb(10.0f));
  EXPECT_EQ(v.le_scale, 2.0f);
  ASSERT_EQ(s.external_files.size(), 1u);
  EXPECT_EQ(s.external_files[0], v.path);
}

TEST(PbrtMedia, CloudReadsEveryParameterWithPbrtDefaults) {
  const SceneDesc s = parse_pbrt(head() +
                                     "MakeNamedMedium \"c\" \"string type\" \"cloud\" \"spectrum sigma_s\" [200 10 900 10]"
                                     " \"spectrum sigma_a\" [200 .01 900 .01] \"float density\" 2 \"float wispiness\" 0.5"
                                     " \"float frequency\" 3 \"float g\" 0.7 \"float scale\" 4 \"point3 p0\" [-1 0 -2]"
                                     " \"point3 p1\" [1 2 3]\n"
                                     "MakeNamedMedium \"plain\" \"string type\" \"cloud\"\n",
                                 "media.pbrt");
  ASSERT_EQ(s.media.size(), 2u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
  EXPECT_FLOAT_EQ(s.media[0].g, 0.7f);
  const auto& c = std::get<CloudMediumDesc>(s.media[0].params);
  EXPECT_EQ(c.sigma_s, Rgb(40.0f));
  EXPECT_NEAR(c.sigma_a.g, 0.04f, 1e-6f);
  EXPECT_EQ(c.density, 2.0f);
  EXPECT_EQ(c.wispiness, 0.5f);
  EXPECT_EQ(c.frequency, 3.0f);
  EXPECT_EQ(c.p0, Vec3f(-1, 0, -2));
  EXPECT_EQ(c.p1, Vec3f(1, 2, 3));
  // pbrt-v4's defaults: density 1, wispiness 1, frequency 5, sigma_a = sigma_s = 1, the unit box.
  const auto& d = std::get<CloudMediumDesc>(s.media[1].params);
  EXPECT_EQ(d.density, 1.0f);
  EXPECT_EQ(d.wispiness, 1.0f);
  EXPECT_EQ(d.frequency, 5.0f);
  EXPECT_EQ(d.sigma_a, Rgb(1.0f));
  EXPECT_EQ(d.sigma_s, Rgb(1.0f));
  EXPECT_EQ(d.p0, Vec3f(0.0f));
  EXPECT_EQ(d.p1, Vec3f(1.0f));
}

void expect_error(const std::string& text, const std::string& where, const std::string& what) {
  const std::string e = error_of(text, tmp("bad.pbrt"));
  EXPECT_NE(e.find(where), std::string::npos) << e;
  EXPECT_NE(e.find(what), std::string::npos) << e;
}

TEST(PbrtMedia, MalformedMediaAreErrorsNamingFileAndLine) {
  const std::string at6 = "bad.pbrt: line 6";
  expect_error(head() + "MakeNamedMedium \"s\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"float density\" [1]\n",
               at6, "\"density\" has 1 values; nx * ny * nz = 2 * 1 * 1 = 2");
  expect_error(head() + "MakeNamedMedium \"s\" \"string type\" \"uniformgrid\" \"float density\" [-1]\n", at6,
               "\"density\" value 0 is negative");
  expect_error(head() + "MakeNamedMedium \"f\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [1 -1 1]\n", at6,
               "must not be negative");
  expect_error(head() + "MakeNamedMedium \"f\" \"string type\" \"homogeneous\" \"spectrum sigma_s\" [400 -2 700 -2]\n",
               at6, "must not be negative");
  expect_error(head() + "MakeNamedMedium \"f\" \"string type\" \"homogeneous\" \"float scale\" -1\n", at6,
               "\"scale\" must not be negative");
  expect_error(head() + "MakeNamedMedium \"f\" \"string type\" \"lava\"\n", at6, "unknown medium type \"lava\"");
  expect_error(head() + "MakeNamedMedium \"f\"\n", at6, "needs a \"string type\"");
  expect_error(head() + kFog + kFog, "bad.pbrt: line 7", "a medium named \"fog\" is already defined");
  expect_error(head() + "MakeNamedMedium \"f\" \"string type\" \"uniformgrid\" \"float density\" [1] \"float "
                        "temperature\" [900] \"rgb Le\" [1 1 1]\n",
               at6, "either \"Le\" or \"temperature\"");
  expect_error(head() + "MakeNamedMedium \"f\" \"string type\" \"homogeneous\" \"float g\" 1.5\n", at6, "\"g\"");
  // An unknown name in MediumInterface: the line of the MediumInterface, whenever the file ends.
  expect_error(head() + kFog + "\nMediumInterface \"fgo\" \"\"\nShape \"sphere\"\n", "bad.pbrt: line 8 (MediumInterface)",
               "no medium named \"fgo\"");
  expect_error(head("nowhere"), "bad.pbrt: line 2 (MediumInterface)", "no medium named \"nowhere\"");
}

TEST(PbrtMedia, MalformedCloudsAreErrorsNamingFileAndLine) {
  const std::string at6 = "bad.pbrt: line 6";
  const std::string cloud = "MakeNamedMedium \"c\" \"string type\" \"cloud\" ";
  expect_error(head() + cloud + "\"float density\" -1\n", at6, "\"density\" must not be negative");
  expect_error(head() + cloud + "\"float scale\" -0.5\n", at6, "\"scale\" must not be negative");
  expect_error(head() + cloud + "\"float wispiness\" -2\n", at6, "\"wispiness\" must not be negative");
  expect_error(head() + cloud + "\"float frequency\" 0\n", at6, "\"frequency\" must be positive");
  expect_error(head() + cloud + "\"rgb sigma_s\" [1 -1 1]\n", at6 + " (MakeNamedMedium \"c\"): parameter \"sigma_s\"", "must not be negative");
  expect_error(head() + cloud + "\"point3 p0\" [0 2 0]\n", at6, "\"p0\" must lie below \"p1\"");
}

TEST(PbrtMedia, MissingOrForeignNanoVdbFilesAreErrorsAtTheirLine) {
  expect_error(head() + "MakeNamedMedium \"c\" \"string type\" \"nanovdb\" \"string filename\" \"absent.nvdb\"\n",
               "bad.pbrt: line 6", "cannot find \"absent.nvdb\"");
  std::ofstream(tmp("text.nvdb")) << "not a volume";
  expect_error(head() + "MakeNamedMedium \"c\" \"string type\" \"nanovdb\" \"string filename\" \"text.nvdb\"\n",
               "bad.pbrt: line 6", "is not a NanoVDB file");
  expect_error(head() + "MakeNamedMedium \"c\" \"string type\" \"nanovdb\"\n", "bad.pbrt: line 6", "needs a \"filename\"");
}

}  // namespace
}  // namespace kiln
