// The pbrt-v4 loader's quadrics (disk, cylinder, partial sphere), shapes' "alpha" and image "infinite" lights:
// parameters and defaults, orientation (ReverseOrientation, mirroring transforms), area lights, instancing, the
// files they name (resolved, listed in SceneDesc::external_files) and bad input (file and line in every message).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scenes/pbrt/loader.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

const std::string kHead =
    "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 8 "
    "\"integer yresolution\" 8\nWorldBegin\n";  // the world starts on line 5

// A folder holding scene.pbrt's neighbours: an environment map and an alpha image (the loader only resolves them).
std::string folder() {
  const fs::path d = fs::path(KILN_TEST_TMP) / "pbrt_quadric_alpha_env";
  fs::create_directories(d / "tex");
  std::ofstream(d / "tex" / "sky.exr") << "not read by the loader";
  std::ofstream(d / "tex" / "leaf.png") << "not read by the loader";
  return d.string();
}

SceneDesc parse(const std::string& world) { return parse_pbrt(kHead + world, folder() + "/scene.pbrt"); }

std::string error_of(const std::string& world) {
  try {
    parse(world);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool has_warning(const SceneDesc& s, const std::string& what) {
  for (const std::string& w : s.warnings)
    if (w.find(what) != std::string::npos) return true;
  return false;
}

TEST(PbrtQuadrics, DiskCylinderAndPartialSphereWithPbrtsDefaults) {
  const SceneDesc s = parse(
      "Shape \"disk\"\n"
      "Shape \"disk\" \"float radius\" 2 \"float innerradius\" 0.5 \"float height\" 0.3 \"float phimax\" 90\n"
      "Shape \"cylinder\"\n"
      "Shape \"cylinder\" \"float radius\" 0.5 \"float zmin\" 2 \"float zmax\" -1 \"float phimax\" 400\n"
      "Shape \"sphere\" \"float radius\" 2 \"float zmin\" -3 \"float zmax\" 1\n"
      "Shape \"sphere\" \"float phimax\" 180\n"
      "Shape \"sphere\" \"float radius\" 2 \"float zmin\" -2 \"float zmax\" 2\n");
  ASSERT_EQ(s.quadrics.size(), 6u);
  ASSERT_EQ(s.spheres.size(), 1u) << "a sphere without cut-aways stays a sphere";
  const Quadric& d0 = s.quadrics[0].quadric;
  EXPECT_EQ(d0.type, QuadricType::Disk);
  EXPECT_EQ(d0.radius, 1.0f);
  EXPECT_EQ(d0.inner_radius, 0.0f);
  EXPECT_EQ(d0.height, 0.0f);
  EXPECT_FLOAT_EQ(d0.phi_max, 2.0f * kPi);
  const Quadric& d1 = s.quadrics[1].quadric;
  EXPECT_EQ(d1.radius, 2.0f);
  EXPECT_EQ(d1.inner_radius, 0.5f);
  EXPECT_EQ(d1.height, 0.3f);
  EXPECT_FLOAT_EQ(d1.phi_max, 0.5f * kPi);
  const Quadric& c0 = s.quadrics[2].quadric;
  EXPECT_EQ(c0.type, QuadricType::Cylinder);
  EXPECT_EQ(c0.z_min, -1.0f);
  EXPECT_EQ(c0.z_max, 1.0f);
  const Quadric& c1 = s.quadrics[3].quadric;
  EXPECT_EQ(c1.z_min, -1.0f) << "zmin and zmax put in order, as pbrt does";
  EXPECT_EQ(c1.z_max, 2.0f);
  EXPECT_FLOAT_EQ(c1.phi_max, 2.0f * kPi) << "phimax clamped to 360";
  const Quadric& s0 = s.quadrics[4].quadric;
  EXPECT_EQ(s0.type, QuadricType::Sphere);
  EXPECT_EQ(s0.z_min, -2.0f) << "clamped to the radius";
  EXPECT_EQ(s0.z_max, 1.0f);
  EXPECT_FLOAT_EQ(s.quadrics[5].quadric.phi_max, kPi);
  for (const std::string& u : s.unsupported) EXPECT_EQ(u.find("sphere"), std::string::npos) << u;
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(PbrtQuadrics, OrientationAreaLightsAndInstances) {
  const SceneDesc s = parse(
      "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [3 2 1]\nReverseOrientation\n"
      "Shape \"disk\" \"float radius\" 1.5\nAttributeEnd\n"
      "AttributeBegin\nScale -1 1 1\nShape \"cylinder\"\nAttributeEnd\n"
      "AttributeBegin\nScale -1 1 1\nReverseOrientation\nAreaLightSource \"diffuse\" \"bool twosided\" true\n"
      "Shape \"sphere\" \"float zmin\" 0\nAttributeEnd\n"
      "ObjectBegin \"pair\"\nShape \"disk\"\nShape \"cylinder\" \"float zmax\" 0.5\nObjectEnd\n"
      "Translate 4 0 0\nObjectInstance \"pair\"\n");
  ASSERT_EQ(s.quadrics.size(), 5u);
  EXPECT_TRUE(s.quadrics[0].flip);
  ASSERT_TRUE(s.quadrics[0].emission);
  EXPECT_EQ(*s.quadrics[0].emission, Rgb(3, 2, 1));
  EXPECT_FALSE(s.quadrics[0].two_sided_emission);
  EXPECT_TRUE(s.quadrics[1].flip) << "a mirroring transform flips, as ReverseOrientation does";
  EXPECT_FALSE(s.quadrics[2].flip) << "both together cancel";
  EXPECT_TRUE(s.quadrics[2].two_sided_emission);
  EXPECT_FALSE(s.quadrics[1].emission);
  // The instance's quadrics, placed by the instance's transform.
  EXPECT_EQ(s.quadrics[3].quadric.type, QuadricType::Disk);
  EXPECT_EQ(s.quadrics[4].quadric.z_max, 0.5f);
  EXPECT_EQ(s.quadrics[4].to_world.point({0, 0, 0}).x, 4.0f);
}

TEST(PbrtQuadrics, BadParametersNameFileAndLine) {
  for (const char* shape :
       {"Shape \"disk\" \"float radius\" -1", "Shape \"cylinder\" \"float radius\" 0",
        "Shape \"sphere\" \"float radius\" -2", "Shape \"disk\" \"float innerradius\" 2",
        "Shape \"cylinder\" \"float zmin\" 1 \"float zmax\" 1",
        "Shape \"sphere\" \"float zmin\" 0.5 \"float radius\" 0.4 \"float zmax\" 0.45"}) {
    const std::string e = error_of(std::string(shape) + "\n");
    EXPECT_NE(e.find("scene.pbrt: line 5 (Shape"), std::string::npos) << shape << ": " << e;
  }
  EXPECT_NE(error_of("Shape \"disk\" \"float radius\" -1\n").find("\"radius\" must be positive"), std::string::npos);
}

TEST(PbrtQuadrics, PbrtV3QuadricsAreWarnedAndSkipped) {
  const SceneDesc s = parse("Shape \"cone\"\nShape \"paraboloid\" \"float radius\" 2\nShape \"hyperboloid\"\n");
  EXPECT_TRUE(s.quadrics.empty());
  EXPECT_TRUE(has_warning(s, "line 6 (Shape \"paraboloid\"): shape \"paraboloid\" is a pbrt-v3 shape"));
  EXPECT_EQ(s.warnings.size(), 3u);
}

TEST(PbrtAlpha, ConstantsConstantTexturesAndFloatImages) {
  const SceneDesc s = parse(
      "Texture \"half\" \"float\" \"constant\" \"float value\" 0.5\n"
      "Texture \"leaf\" \"float\" \"imagemap\" \"string filename\" \"tex/leaf.png\" \"float uscale\" 2 "
      "\"float vdelta\" 0.25 \"bool invert\" true\n"
      "Texture \"lin\" \"float\" \"imagemap\" \"string filename\" \"tex/leaf.png\" \"string encoding\" \"linear\" "
      "\"string filter\" \"point\"\n"
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0] \"float alpha\" 0.25\n"
      "Shape \"sphere\" \"texture alpha\" \"half\"\n"
      "Shape \"disk\" \"texture alpha\" \"leaf\"\n"
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0] \"texture alpha\" \"leaf\"\n"
      "Shape \"cylinder\" \"texture alpha\" \"lin\"\n"
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0]\n");
  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.meshes[0].alpha.value, 0.25f);
  EXPECT_TRUE(s.meshes[0].alpha.cuts());
  EXPECT_FALSE(s.meshes[2].alpha.cuts());
  EXPECT_EQ(s.spheres[0].alpha.value, 0.5f);
  const ShapeAlphaDesc& leaf = s.quadrics[0].alpha;
  ASSERT_GE(leaf.texture, 0);
  EXPECT_EQ(s.meshes[1].alpha.texture, leaf.texture) << "one scene texture per pbrt texture";
  EXPECT_EQ(leaf.image.encoding, AlphaEncoding::Srgb) << "pbrt's default for PNG files";
  EXPECT_EQ(leaf.image.su, 2.0f);
  EXPECT_EQ(leaf.image.dv, 0.25f);
  EXPECT_TRUE(leaf.image.invert);
  const TextureDesc& t = s.textures.at(size_t(leaf.texture));
  EXPECT_EQ(fs::path(t.image_path).filename(), "leaf.png");
  EXPECT_TRUE(fs::exists(t.image_path));
  const ShapeAlphaDesc& lin = s.quadrics[1].alpha;
  EXPECT_EQ(lin.image.encoding, AlphaEncoding::Linear);
  EXPECT_EQ(s.textures.at(size_t(lin.texture)).filter, TextureFilter::Nearest);
  EXPECT_EQ(std::count(s.external_files.begin(), s.external_files.end(), t.image_path), 2) << "both textures";
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(PbrtAlpha, ASpectrumTextureOrAMissingOneIsAnErrorWithFileAndLine) {
  const std::string spectrum = error_of(
      "Texture \"c\" \"spectrum\" \"constant\" \"rgb value\" [1 1 1]\n"
      "Shape \"disk\" \"texture alpha\" \"c\"\n");
  EXPECT_NE(spectrum.find("scene.pbrt: line 6 (Shape \"disk\")"), std::string::npos) << spectrum;
  EXPECT_NE(spectrum.find("a spectrum texture"), std::string::npos) << spectrum;
  const std::string missing = error_of("Shape \"disk\" \"texture alpha\" \"nope\"\n");
  EXPECT_NE(missing.find("scene.pbrt: line 5"), std::string::npos) << missing;
  const std::string image = error_of("Texture \"x\" \"float\" \"imagemap\" \"string filename\" \"tex/absent.png\"\n");
  EXPECT_NE(image.find("scene.pbrt: line 5 (Texture \"x\")"), std::string::npos) << image;
  EXPECT_NE(image.find("absent.png"), std::string::npos) << image;
}

TEST(PbrtImageInfiniteLight, AnEqualAreaMapInTheLightsFrame) {
  const SceneDesc s = parse(
      "AttributeBegin\nRotate -90 1 0 0\n"
      "LightSource \"infinite\" \"string filename\" \"tex/sky.exr\" \"float scale\" 2.5 \"float illuminance\" 7\n"
      "AttributeEnd\n");
  ASSERT_EQ(s.env_lights.size(), 1u);
  const EnvLightDesc& e = s.env_lights[0];
  EXPECT_EQ(e.format, EnvMapFormat::EqualArea);
  EXPECT_TRUE(e.lat_long_if_not_square);
  EXPECT_EQ(fs::path(e.image_path).filename(), "sky.exr");
  EXPECT_TRUE(fs::exists(e.image_path));
  EXPECT_EQ(e.scale, 2.5f);
  ASSERT_TRUE(e.illuminance);
  EXPECT_EQ(*e.illuminance, 7.0f);
  // The map's +z (its zenith) is the world's +y after Rotate -90 about x.
  const Vec3f up = e.light_to_world.vector({0, 0, 1});
  EXPECT_NEAR(up.y, 1.0f, 1e-6f);
  EXPECT_NE(e.element.find("line 7 (LightSource \"infinite\")"), std::string::npos) << e.element;
  ASSERT_EQ(s.external_files.size(), 1u);
  EXPECT_EQ(s.external_files[0], e.image_path);
  EXPECT_TRUE(s.infinite_lights.empty());
  EXPECT_TRUE(s.unsupported.empty());
}

TEST(PbrtImageInfiniteLight, PortalsAreWarnedAndBadInputNamesFileAndLine) {
  const SceneDesc s = parse(
      "LightSource \"infinite\" \"string filename\" \"tex/sky.exr\" \"point3 portal\" [0 0 0 1 0 0 1 1 0 0 1 0]\n");
  EXPECT_TRUE(has_warning(s, "line 5 (LightSource \"infinite\"): \"portal\" is ignored"));
  const std::string missing = error_of("LightSource \"infinite\" \"string filename\" \"tex/nowhere.exr\"\n");
  EXPECT_NE(missing.find("scene.pbrt: line 5 (LightSource \"infinite\")"), std::string::npos) << missing;
  EXPECT_NE(missing.find("nowhere.exr"), std::string::npos) << missing;
  const std::string both =
      error_of("LightSource \"infinite\" \"string filename\" \"tex/sky.exr\" \"rgb L\" [1 1 1]\n");
  EXPECT_NE(both.find("line 5"), std::string::npos) << both;
}

}  // namespace
}  // namespace kiln
