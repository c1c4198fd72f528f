// pbrt-v4 loader: tokens, typed parameters, transforms, camera, shapes, materials, lights, instancing, includes,
// warnings and errors, on inline text and on the files in tests/data/pbrt/ (whose comments state the answers).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scenes/gzip_file.h"
#include "scenes/loader.h"
#include "scenes/pbrt/loader.h"
#include "scenes/pbrt/spectrum.h"
#include "scenes/pbrt/tokenizer.h"
#include "support/shared_data.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

const std::string kData = std::string(KILN_SOURCE_DIR) + "/tests/data/pbrt/";
// A minimal options block so that inline tests only write their world.
const std::string kHead =
    "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 8 "
    "\"integer yresolution\" 8\nWorldBegin\n";  // the world starts on line 5

std::string tmp(const std::string& sub) {
  const fs::path d = fs::path(KILN_TEST_TMP) / "pbrt_loader" / sub;
  fs::create_directories(d);
  return d.string();
}

void write(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

SceneDesc parse(const std::string& text, const std::string& path = "inline.pbrt") { return parse_pbrt(text, path); }

// The kiln::Error message, or "" when the text loads.
std::string error_of(const std::string& text, const std::string& path = "inline.pbrt") {
  try {
    parse_pbrt(text, path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool has_warning(const SceneDesc& s, const std::string& a, const std::string& b = "") {
  for (const std::string& w : s.warnings)
    if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
  return false;
}

std::string all_warnings(const SceneDesc& s) {
  std::string out;
  for (const std::string& w : s.warnings) out += w + "\n";
  return out;
}

void expect_near(Vec3f a, Vec3f b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

void expect_near(Rgb a, Rgb b, float tol = 1e-5f) {
  EXPECT_NEAR(a.r, b.r, tol);
  EXPECT_NEAR(a.g, b.g, tol);
  EXPECT_NEAR(a.b, b.b, tol);
}

// Normal-incidence reflectance of a conductor with complex index eta + i k (in air).
double conductor_reflectance(double eta, double k) {
  return ((eta - 1) * (eta - 1) + k * k) / ((eta + 1) * (eta + 1) + k * k);
}

// Gold's normal-incidence reflectance at 630, 532 and 465 nm from measured optical constants (Yakubovsky et al.,
// "Optical constants and structural properties of thin gold films", Opt. Express 25, 2017, 53 nm film:
// n, k = 0.197, 3.561 / 0.489, 2.328 / 1.455, 1.929): 0.944, 0.744, 0.403. Kiln's RGB reduction of pbrt's
// "metal-Au-eta" / "metal-Au-k" integrates over each channel's band, so it agrees within 0.1, not exactly; swapped
// channels, swapped eta and k or another metal miss by far more.
void expect_gold(Rgb eta, Rgb k) {
  const double measured[3] = {conductor_reflectance(0.197, 3.561), conductor_reflectance(0.489, 2.328),
                              conductor_reflectance(1.455, 1.929)};
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(conductor_reflectance(eta[c], k[c]), measured[c], 0.1) << "channel " << c;
}

// ---- tokens and parameters ----

TEST(PbrtTokenizer, WordsStringsBracketsCommentsAndLines) {
  PbrtTokenizer t("Shape\"a b\"[1 2]# comment \"not a string\n  \"esc\\\"aped\\n\" x#y\n", "t.pbrt");
  std::vector<PbrtToken> toks;
  while (auto k = t.next()) toks.push_back(*k);
  ASSERT_EQ(toks.size(), 8u);
  EXPECT_TRUE(toks[0].is_word("Shape"));
  EXPECT_EQ(toks[1].kind, PbrtTokenKind::String);
  EXPECT_EQ(toks[1].text, "a b");
  EXPECT_EQ(toks[2].kind, PbrtTokenKind::OpenBracket);
  EXPECT_TRUE(toks[3].is_word("1"));
  EXPECT_EQ(toks[5].kind, PbrtTokenKind::CloseBracket);
  EXPECT_EQ(toks[6].line, 2);
  EXPECT_EQ(pbrt_unescape(toks[6], "t.pbrt"), "esc\"aped\n");
  EXPECT_TRUE(toks[7].is_word("x#y"));  // as in pbrt, '#' starts a comment only where a token would start
}

TEST(PbrtTokenizer, UnterminatedStringsAreErrorsWithTheLine) {
  PbrtTokenizer a("\n\n\"abc\ndef\"", "a.pbrt");
  try {
    a.next();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a.pbrt: line 3"), std::string::npos) << e.what();
  }
  PbrtTokenizer b("\"abc", "b.pbrt");
  EXPECT_THROW(b.next(), Error);
  PbrtTokenizer c("\"a\\qb\"", "c.pbrt");
  const auto tok = c.next();
  ASSERT_TRUE(tok);
  EXPECT_THROW(pbrt_unescape(*tok, "c.pbrt"), Error);
}

TEST(PbrtParams, EveryTypeBracketedOrBare) {
  const SceneDesc s =
      parse(kHead +
            "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n"
            "  \"normal N\" [0 0 1 0 0 1 0 0 1] \"point2 uv\" [0 0 1 0 0 1]\n"
            "AttributeBegin\n AreaLightSource \"diffuse\" \"rgb L\" [1 2 3] \"bool twosided\" \"true\"\n"
            " Shape \"sphere\" \"float radius\" 2.5\nAttributeEnd\n");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(s.meshes[0].normals.size(), 3u);
  EXPECT_EQ(s.meshes[0].uvs.size(), 3u);
  ASSERT_EQ(s.spheres.size(), 1u);
  EXPECT_EQ(s.spheres[0].radius, 2.5f);
  EXPECT_EQ(*s.spheres[0].emission, Rgb(1, 2, 3));
  ASSERT_EQ(s.warnings.size(), 1u) << all_warnings(s);
  EXPECT_TRUE(has_warning(s, "line 9 (Shape \"sphere\")", "two-sided sphere light")) << all_warnings(s);
}

TEST(PbrtParams, BadValuesAreErrorsNamingFileLineAndDirective) {
  struct Case {
    std::string text, expect;
  };
  const Case cases[] = {
      {"Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2.5]", "expected an integer"},
      {"Shape \"sphere\" \"float radius\" [ abc ]", "expected a finite number"},
      {"Shape \"sphere\" \"float radius\" [ 1e999 ]", "expected a finite number"},
      {"Shape \"sphere\" \"float radius\" [ 1 2 ]", "takes one value"},
      {"Shape \"sphere\" \"integer radius\" [ 1 ]", "is declared \"integer\""},
      {"Shape \"sphere\" \"colour radius\" [ 1 ]", "unknown parameter type"},
      {"Shape \"sphere\" \"float\" 1", "\"type name\""},
      {"Shape \"sphere\" \"float radius\" [ 1", "closing ']'"},
      {"Shape \"sphere\" \"float radius\" ]", "']' without '['"},
      {"Shape \"sphere\" \"string radius\" 1", "expected a quoted string"},
      {"Shape \"trianglemesh\" \"point3 P\" [0 0 0 1]", "not a multiple of 3"},
      {"AreaLightSource \"diffuse\" \"bool twosided\" \"yes\"", "expected true or false"},
      {"AreaLightSource \"diffuse\" \"rgb L\" [1 2]", "not a multiple of 3"},
      {"AreaLightSource \"diffuse\" \"rgb L\" [-1 2 3]", "negative"},
      {"Material \"diffuse\" \"rgb reflectance\" [0.5 1.5 0.5]", "at most 1"},
      {"AreaLightSource \"diffuse\" \"blackbody L\" [-5]", "positive"},
      {"AreaLightSource \"diffuse\" \"spectrum L\" [500 1 400 2]", "wavelengths must increase"},
      {"AreaLightSource \"diffuse\" \"spectrum L\" \"no-such-spectrum\"", "is not a named spectrum (nearest: "},
  };
  for (const Case& c : cases) {
    const std::string e = error_of(kHead + c.text + "\n");
    EXPECT_NE(e.find("inline.pbrt: line 5"), std::string::npos) << c.text << " -> " << e;
    EXPECT_NE(e.find(c.expect), std::string::npos) << c.text << " -> " << e;
  }
}

TEST(PbrtParams, UnusedParametersAreWarnedWithTheirLine) {
  const SceneDesc s = parse(kHead + "Shape \"sphere\"\n  \"float radius\" 1\n  \"float zap\" 3\n");
  EXPECT_TRUE(has_warning(s, "inline.pbrt: line 7 (Shape \"sphere\")", "\"float zap\" is not used")) << all_warnings(s);
}

// pbrt-v4 looks a parameter up from the end of its list, so a name given twice keeps its last value (the
// collection's villa materials do it); Kiln says so on the second one's line.
TEST(PbrtParams, AParameterGivenTwiceKeepsItsLastValue) {
  const SceneDesc s = parse(kHead + "Shape \"sphere\" \"float radius\" 1\n  \"float radius\" 2\n");
  ASSERT_EQ(s.spheres.size(), 1u);
  EXPECT_FLOAT_EQ(s.spheres[0].radius, 2.0f);
  EXPECT_TRUE(has_warning(s, "inline.pbrt: line 6 (Shape \"sphere\")", "\"radius\" is given twice (first on line 5)"))
      << all_warnings(s);
}

// ---- errors the issue names ----

TEST(PbrtErrors, UnknownDirectiveMissingWorldBeginUnbalancedAttributesMissingInclude) {
  EXPECT_NE(error_of(kHead + "Frobnicate 1 2\n").find("line 5: unknown directive 'Frobnicate'"), std::string::npos);
  EXPECT_NE(error_of("Camera \"perspective\"\nShape \"sphere\"\n").find("line 2 (Shape): Shape before WorldBegin"),
            std::string::npos);
  EXPECT_NE(error_of("Camera \"perspective\"\n\n").find("missing WorldBegin"), std::string::npos);
  EXPECT_NE(error_of(kHead + "AttributeBegin\nAttributeEnd\nAttributeEnd\n").find("line 7 (AttributeEnd)"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "ObjectBegin \"a\"\nAttributeEnd\n").find("closes the ObjectBegin"), std::string::npos);
  const std::string inc = error_of(kHead + "Include \"nope/missing.pbrt\"\n");
  EXPECT_NE(inc.find("line 5 (Include): cannot find \"nope/missing.pbrt\""), std::string::npos) << inc;
  EXPECT_NE(error_of(kHead + "WorldBegin\n").find("appears twice"), std::string::npos);
  EXPECT_NE(error_of(kHead + "Camera \"perspective\"\n").find("after WorldBegin"), std::string::npos);
  EXPECT_NE(error_of(kHead + "ObjectInstance \"none\"\n").find("no object named \"none\""), std::string::npos);
  EXPECT_NE(error_of(kHead + "NamedMaterial \"none\"\n").find("no material named"), std::string::npos);
  EXPECT_NE(error_of(kHead + "ObjectBegin \"a\"\n").find("no ObjectEnd"), std::string::npos);
  EXPECT_NE(error_of(kHead + "Translate 1 2\n").find("line 5 (Translate): the file ends inside"), std::string::npos);
  EXPECT_NE(error_of(kHead + "Translate 1 2 x\n").find("expected a finite number, got 'x'"), std::string::npos);
  // pbrt accepts a singular transform; only what needs its inverse fails, naming the shape's line.
  EXPECT_NE(error_of(kHead + "Scale 1 0 1\nShape \"sphere\"\n").find("line 6 (Shape \"sphere\"): the transform is singular"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "Rotate 30 0 0 0\n").find("line 5 (Rotate)"), std::string::npos);
  EXPECT_NE(error_of(kHead + "\"stray\"\n").find("expected a directive"), std::string::npos);
  EXPECT_NE(error_of("Camera \"fisheye\"\nWorldBegin\n").find("unknown camera \"fisheye\""), std::string::npos);
  EXPECT_NE(error_of("Scale 1 1 0\nCamera \"perspective\"\nWorldBegin\n").find("line 2 (Camera \"perspective\"): the camera "
                                                                            "transform is singular"),
            std::string::npos);
  EXPECT_NE(error_of("LookAt 0 0 0  0 0 0  0 1 0\n").find("coincide"), std::string::npos);
  EXPECT_NE(error_of("LookAt 0 0 0  0 1 0  0 1 0\n").find("parallel"), std::string::npos);
}

TEST(PbrtErrors, MeshDataIsCheckedAgainstItsCounts) {
  EXPECT_NE(error_of(kHead + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 3]\n")
                .find("value 3 (entry 2) is out of range"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n")
                .find("needs \"integer indices\""),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"normal N\" [0 0 1]\n")
                .find("\"N\" has 1 normals"),
            std::string::npos);
  EXPECT_NE(
      error_of(kHead + "Shape \"loopsubdiv\" \"integer levels\" 9 \"point3 P\" [0 0 0 1 0 0 0 1 0]\n").find("levels"),
      std::string::npos);
  EXPECT_NE(error_of(kHead + "Shape \"plymesh\" \"string filename\" \"none.ply\"\n").find("cannot find \"none.ply\""),
            std::string::npos);
}

// pbrt reads tokens across the end of an included file: a parameter list the included file ends goes on in the
// including file (the quad's indices come after the Include), with a note; the next directive ends it as usual.
TEST(PbrtIncludes, ParameterListsContinueAfterTheIncludedFileEnds) {
  const std::string dir = tmp("include_continues");
  write(dir + "/quad.pbrt", "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n");
  const SceneDesc s = parse(kHead + "Include \"quad.pbrt\"\n  \"integer indices\" [0 1 2 0 2 3]\nShape \"sphere\"\n",
                            dir + "/main.pbrt");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices.size(), 6u);
  EXPECT_EQ(s.spheres.size(), 1u);
  EXPECT_TRUE(has_warning(s, "quad.pbrt: line 1", "goes on after the end of this file")) << all_warnings(s);
}

// pbrt-v4 looks named materials up once the whole file is read: a shape may use a name defined further down (as
// the collection's contemporary-bathroom does, before its Include of materials.pbrt). A name defined nowhere is an
// error naming the line that used it.
TEST(PbrtMaterials, NamedMaterialsMayBeUsedBeforeTheyAreDefined) {
  const SceneDesc s = parse(kHead + "NamedMaterial \"later\"\nShape \"sphere\"\nNamedMaterial \"now\"\nShape \"sphere\"\n"
                                    "MakeNamedMaterial \"later\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.2 0.3 0.4]\n"
                                    "MakeNamedMaterial \"now\" \"string type\" \"conductor\"\n"
                                    "NamedMaterial \"now\"\nShape \"sphere\"\n");
  ASSERT_EQ(s.spheres.size(), 3u);
  ASSERT_EQ(s.materials.size(), 2u) << "one material per name, the slot filled by the definition";
  const auto& later = s.materials[size_t(s.spheres[0].material)];
  EXPECT_EQ(later.pbrt->kind, PbrtMaterialKind::Diffuse);
  EXPECT_EQ(later.pbrt->reflectance, Rgb(0.2f, 0.3f, 0.4f));
  EXPECT_EQ(later.id, s.spheres[0].material + 1);
  EXPECT_EQ(s.materials[size_t(s.spheres[1].material)].pbrt->kind, PbrtMaterialKind::Conductor);
  EXPECT_EQ(s.spheres[2].material, s.spheres[1].material);
  const std::string e = error_of(kHead + "Shape \"sphere\"\nNamedMaterial \"nowhere\"\nShape \"sphere\"\n");
  EXPECT_NE(e.find("inline.pbrt: line 6 (NamedMaterial): no material named \"nowhere\""), std::string::npos) << e;
}

TEST(PbrtErrors, ErrorsInIncludedFilesNameThatFileAndTheInclusion) {
  const std::string dir = tmp("include_error");
  write(dir + "/child.pbrt", "Shape \"sphere\"\nShape \"sphere\" \"float radius\" -1\n");
  const std::string e = error_of(kHead + "Include \"child.pbrt\"\n", dir + "/main.pbrt");
  EXPECT_NE(e.find("child.pbrt: line 2 (Shape \"sphere\"): \"radius\" must be positive"), std::string::npos) << e;
  EXPECT_NE(e.find("included from " + dir + "/main.pbrt: line 5"), std::string::npos) << e;
}

// ---- transforms ----

TEST(PbrtTransforms, DirectivesComposeOnTheRightAsPbrtDoes) {
  const SceneDesc s =
      parse(kHead +
            "Translate 1 0 0\nScale 2 2 2\nRotate 90 0 0 1\n"
            "Shape \"trianglemesh\" \"point3 P\" [1 0 0 0 1 0 0 0 1]\n"
            "Identity\nTransform [1 0 0 0 0 1 0 0 0 0 1 0 5 6 7 1]\nConcatTransform [2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1]\n"
            "Shape \"trianglemesh\" \"point3 P\" [1 0 0 0 1 0 0 0 1]\n");
  ASSERT_EQ(s.meshes.size(), 2u);
  // p -> rotate -> scale -> translate: (1,0,0) -> (0,1,0) -> (0,2,0) -> (1,2,0).
  expect_near(s.meshes[0].to_world.point({1, 0, 0}), {1, 2, 0});
  expect_near(s.meshes[1].to_world.point({1, 1, 1}), {7, 8, 9});
}

TEST(PbrtTransforms, CoordinateSystemsAndActiveTransforms) {
  const SceneDesc s = parse(kHead +
                            "Translate 0 0 3\nCoordinateSystem \"up3\"\nIdentity\n"
                            "CoordSysTransform \"up3\"\nShape \"sphere\"\n"
                            "CoordSysTransform \"world\"\nShape \"sphere\"\n"
                            "ActiveTransform StartTime\nTranslate 1 0 0\nActiveTransform All\nShape \"sphere\"\n"
                            "CoordSysTransform \"nowhere\"\n");
  ASSERT_EQ(s.spheres.size(), 3u);
  expect_near(s.spheres[0].to_world.point({0, 0, 0}), {0, 0, 3});
  expect_near(s.spheres[1].to_world.point({0, 0, 0}), {0, 0, 0});
  expect_near(s.spheres[2].to_world.point({0, 0, 0}), {1, 0, 0});
  // ActiveTransform StartTime moved only the start: the sphere moves from x = 1 back to the origin.
  ASSERT_TRUE(s.spheres[2].to_world_motion);
  expect_near(s.spheres[2].to_world_motion->end.point({0, 0, 0}), {0, 0, 0});
  EXPECT_FALSE(s.spheres[0].to_world_motion);
  EXPECT_TRUE(has_warning(s, "line 16 (CoordSysTransform)", "\"nowhere\"")) << all_warnings(s);
}

// pbrt-v4 keeps ActiveTransform in the graphics state: AttributeEnd restores it. A moving mesh becomes an instance
// of itself whose transform moves; a moving sphere keeps its start transform and gains the end one; an emitter
// does not move (warned); TransformTimes are mapped onto the shutter (0 at shutteropen, 1 at shutterclose).
TEST(PbrtTransforms, MovingShapesCarryBothTransformsOnTheShutterScale) {
  const std::string tri = "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n";
  const SceneDesc s = parse(
      "TransformTimes 1 3\nLookAt 0 0 5  0 0 0  0 1 0\n"
      "Camera \"perspective\" \"float shutteropen\" 1 \"float shutterclose\" 5\nWorldBegin\n"
      "AttributeBegin\nActiveTransform EndTime\nTranslate 2 0 0\n" + tri + "AttributeEnd\n" +
      "Translate 0 1 0\n" + tri +  // All again after AttributeEnd: both ends move alike, no motion
      "AttributeBegin\nActiveTransform StartTime\nRotate 90 0 0 1\nShape \"sphere\"\n"
      "AreaLightSource \"diffuse\"\nShape \"sphere\"\nAttributeEnd\n");
  ASSERT_EQ(s.instances.size(), 1u) << "the moving mesh, as an instance";
  const InstanceDesc& moving = s.instances[0];
  EXPECT_FALSE(s.meshes[size_t(moving.base_mesh)].visible);
  ASSERT_TRUE(moving.to_world_motion);
  expect_near(moving.to_world.point({0, 0, 0}), {0, 0, 0});
  expect_near(moving.to_world_motion->end.point({0, 0, 0}), {2, 0, 0});
  EXPECT_FLOAT_EQ(moving.to_world_motion->start_time, 0.0f);  // (1 - 1) / (5 - 1)
  EXPECT_FLOAT_EQ(moving.to_world_motion->end_time, 0.5f);    // (3 - 1) / (5 - 1)
  EXPECT_TRUE(s.meshes.back().visible) << "the static mesh after AttributeEnd";
  ASSERT_EQ(s.spheres.size(), 2u);
  ASSERT_TRUE(s.spheres[0].to_world_motion);
  expect_near(s.spheres[0].to_world.point({1, 0, 0}), {0, 2, 0});
  expect_near(s.spheres[0].to_world_motion->end.point({1, 0, 0}), {1, 1, 0});
  EXPECT_FALSE(s.spheres[1].to_world_motion) << "emitters stay at their start";
  EXPECT_TRUE(has_warning(s, "line 17", "does not move area lights")) << all_warnings(s);
  EXPECT_NE(error_of("TransformTimes 2 1\n" + kHead).find("line 1 (TransformTimes)"), std::string::npos);
  EXPECT_NE(error_of(kHead + "TransformTimes 0 1\n").find("after WorldBegin"), std::string::npos);
  EXPECT_NE(error_of("Camera \"perspective\" \"float shutteropen\" 1 \"float shutterclose\" 1\nWorldBegin\n")
                .find("the shutter never opens"),
            std::string::npos);
}

// An instance placed by a moving transform moves as a whole; a mirrored end with an unmirrored start cannot be
// interpolated (an error naming the line).
TEST(PbrtTransforms, MovingInstancesAndUninterpolableMotion) {
  const SceneDesc s = parse(kHead +
                            "ObjectBegin \"tri\"\nTranslate 0 0 1\n"
                            "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\nObjectEnd\n"
                            "ActiveTransform EndTime\nTranslate 3 0 0\nActiveTransform All\nObjectInstance \"tri\"\n");
  ASSERT_EQ(s.instances.size(), 1u);
  ASSERT_TRUE(s.instances[0].to_world_motion);
  expect_near(s.instances[0].to_world.point({0, 0, 0}), {0, 0, 1});
  expect_near(s.instances[0].to_world_motion->end.point({0, 0, 0}), {3, 0, 1});
  const std::string e = error_of(kHead + "ActiveTransform EndTime\nScale -1 1 1\nShape \"sphere\"\n");
  EXPECT_NE(e.find("line 7 (Shape \"sphere\"): the transform moves over the shutter but cannot be interpolated"),
            std::string::npos)
      << e;
}

// A singular ConcatTransform (pbrt accepts it) flattens a mesh, which needs no inverse; the mesh's normals, which
// would, are dropped with a warning.
TEST(PbrtTransforms, SingularTransformsFlattenMeshes) {
  const SceneDesc s = parse(kHead +
                            "ConcatTransform [1 0 0 0  0 1 0 0  0 0 0 0  0 0 0 1]\n"
                            "Shape \"trianglemesh\" \"point3 P\" [0 0 1 1 0 1 0 1 1] \"normal N\" [0 0 1 0 0 1 0 0 1]\n");
  ASSERT_EQ(s.meshes.size(), 1u);
  expect_near(s.meshes[0].to_world.point({1, 0, 1}), {1, 0, 0});
  EXPECT_FALSE(s.meshes[0].to_world.invertible());
  EXPECT_TRUE(s.meshes[0].normals.empty());
  EXPECT_TRUE(has_warning(s, "line 6", "singular")) << all_warnings(s);
}

TEST(PbrtTransforms, CameraCoordinateSystemIsTheInverseCameraTransform) {
  const SceneDesc s = parse(
      "LookAt 1 2 5  1 2 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
      "CoordSysTransform \"camera\"\nShape \"sphere\"\n");
  ASSERT_EQ(s.spheres.size(), 1u);
  // The eye; camera-from-world itself would put the sphere at (1, -2, 5).
  expect_near(s.spheres[0].to_world.point({0, 0, 0}), {1, 2, 5});
  expect_near(s.spheres[0].to_world.vector({0, 0, 1}), {0, 0, -1});  // camera +z looks down -z
}

// ---- camera ----

TEST(PbrtCamera, LookAtGivesPbrtsLeftHandedCamera) {
  const SceneDesc s = parse(kHead);
  ASSERT_EQ(s.cameras.size(), 1u);
  const CameraDesc& c = s.cameras[0];
  expect_near(c.position, {0, 0, 5});
  expect_near(c.gaze, {0, 0, -1});
  expect_near(c.up, {0, 1, 0});
  EXPECT_TRUE(c.left_handed);
  EXPECT_EQ(c.renderer, RendererKind::PathTracing);
  EXPECT_EQ(s.rules, SceneRules::Kiln);
  EXPECT_EQ(s.format, "pbrt-v4");
  EXPECT_EQ(*s.max_recursion_depth, kPbrtDefaultMaxDepth);
  EXPECT_EQ(c.num_samples, 16);
  EXPECT_EQ(c.image_name, "pbrt.exr");
  ASSERT_TRUE(c.filter);  // pbrt's default: gaussian, radius 1.5, sigma 0.5
  EXPECT_EQ(c.filter->kind, PixelFilterKind::Gaussian);
  EXPECT_EQ(c.filter->radius, 1.5f);
  EXPECT_EQ(c.filter->sigma, 0.5f);
}

TEST(PbrtCamera, FovSpansTheShorterAxis) {
  const float t = std::tan(radians(30.0f));
  for (const auto& [w, h] : {std::pair{50, 100}, std::pair{100, 50}}) {
    const SceneDesc s = parse("Camera \"perspective\" \"float fov\" 60\nFilm \"rgb\" \"integer xresolution\" " +
                              std::to_string(w) + " \"integer yresolution\" " + std::to_string(h) + "\nWorldBegin\n");
    const CameraDesc& c = s.cameras[0];
    EXPECT_FALSE(c.use_fov);
    EXPECT_EQ(c.near_distance, 1.0f);
    const float aspect = float(w) / float(h);
    const float half_x = aspect > 1 ? t * aspect : t, half_y = aspect > 1 ? t : t / aspect;
    EXPECT_NEAR(c.near_plane[0], -half_x, 1e-6f);
    EXPECT_NEAR(c.near_plane[1], half_x, 1e-6f);
    EXPECT_NEAR(c.near_plane[2], -half_y, 1e-6f);
    EXPECT_NEAR(c.near_plane[3], half_y, 1e-6f);
  }
}

TEST(PbrtCamera, DefaultCameraWithoutDirectivesIsPbrts) {
  const SceneDesc s = parse("WorldBegin\n");
  const CameraDesc& c = s.cameras[0];
  EXPECT_EQ(c.width, 1280);
  EXPECT_EQ(c.height, 720);
  expect_near(c.position, {0, 0, 0});
  expect_near(c.gaze, {0, 0, 1});
  EXPECT_NEAR(c.near_plane[3], 1.0f, 1e-6f);  // fov 90 on the shorter axis
}

TEST(PbrtCamera, FiltersAndTheirRadii) {
  auto filter_of = [](const std::string& f) { return *parse("PixelFilter " + f + "\nWorldBegin\n").cameras[0].filter; };
  EXPECT_EQ(filter_of("\"box\"").kind, PixelFilterKind::Box);
  EXPECT_EQ(filter_of("\"box\"").radius, 0.5f);
  EXPECT_EQ(filter_of("\"box\" \"float xradius\" 1 \"float yradius\" 1").radius, 1.0f);
  const PixelFilterDesc g = filter_of("\"gaussian\" \"float xradius\" 3 \"float yradius\" 3 \"float sigma\" 0.9");
  EXPECT_EQ(g.kind, PixelFilterKind::Gaussian);
  EXPECT_EQ(g.radius, 3.0f);
  EXPECT_EQ(g.sigma, 0.9f);
  EXPECT_EQ(filter_of("\"triangle\"").kind, PixelFilterKind::Triangle);
  EXPECT_EQ(filter_of("\"triangle\"").radius, 2.0f);
  const PixelFilterDesc m = filter_of("\"mitchell\" \"float B\" 0.5 \"float C\" 0.25");
  EXPECT_EQ(m.kind, PixelFilterKind::Mitchell);
  EXPECT_EQ(m.b, 0.5f);
  EXPECT_EQ(m.c, 0.25f);
  const SceneDesc uneven = parse("PixelFilter \"box\" \"float xradius\" 1 \"float yradius\" 2\nWorldBegin\n");
  EXPECT_TRUE(has_warning(uneven, "line 1 (PixelFilter \"box\")", "different x and y radii")) << all_warnings(uneven);
}

// ---- the file with every directive (its comments give these values) ----

class PbrtAllDirectives : public ::testing::Test {
 protected:
  void SetUp() override { s = load_pbrt(kData + "all_directives.pbrt"); }
  SceneDesc s;
};

TEST_F(PbrtAllDirectives, OptionsBlock) {
  ASSERT_EQ(s.cameras.size(), 1u);
  const CameraDesc& c = s.cameras[0];
  expect_near(c.position, {1, 2, 3});
  expect_near(c.gaze, {0, 0, -1});
  expect_near(c.up, {0, 1, 0});
  EXPECT_FALSE(c.left_handed);  // Scale -1 1 1 mirrors the camera
  EXPECT_EQ(c.width, 20);
  EXPECT_EQ(c.height, 10);
  const float t = std::tan(radians(15.0f));
  EXPECT_NEAR(c.near_plane[0], -t, 1e-6f);
  EXPECT_NEAR(c.near_plane[1], t, 1e-6f);
  EXPECT_NEAR(c.near_plane[2], 0.0f, 1e-6f);
  EXPECT_NEAR(c.near_plane[3], t, 1e-6f);
  EXPECT_TRUE(c.disk_lens);
  EXPECT_NEAR(c.aperture_size, 0.1f, 1e-6f);
  EXPECT_NEAR(c.focus_distance, 2.5f, 1e-6f);
  EXPECT_EQ(c.image_name, "all.exr");
  EXPECT_EQ(c.num_samples, 32);
  EXPECT_EQ(*s.max_recursion_depth, 7);
  ASSERT_TRUE(c.filter);
  EXPECT_EQ(c.filter->kind, PixelFilterKind::Gaussian);
  EXPECT_EQ(c.filter->radius, 2.0f);
  EXPECT_EQ(c.filter->sigma, 0.7f);
  EXPECT_TRUE(has_warning(s, "line 12 (Sampler \"halton\")", "Kiln's stratified sampler")) << all_warnings(s);
}

TEST_F(PbrtAllDirectives, ShapesAndTheirTransforms) {
  ASSERT_EQ(s.spheres.size(), 2u);
  EXPECT_EQ(s.spheres[0].radius, 0.75f);
  expect_near(s.spheres[0].to_world.point({0, 0, 0}), {0, 0, 0});
  EXPECT_EQ(s.spheres[1].radius, 2.0f);
  expect_near(s.spheres[1].to_world.point({0, 0, 0}), {0, 5, 0});
  ASSERT_EQ(s.meshes.size(), 5u);
  EXPECT_EQ(s.meshes[0].normals.size(), 3u);
  EXPECT_EQ(s.meshes[0].uvs.size(), 3u);
  EXPECT_EQ(s.meshes[1].indices, (std::vector<uint32_t>{0, 1, 3, 0, 3, 2}));
  expect_near(s.meshes[1].to_world.point({1, 1, 0}), {7, 8, 7});
  EXPECT_EQ(s.meshes[2].subdivide, 2);
  EXPECT_TRUE(s.meshes[2].smooth);
  EXPECT_EQ(s.meshes[4].indices, (std::vector<uint32_t>{0, 2, 1}));
}

TEST_F(PbrtAllDirectives, Materials) {
  auto pbrt_of = [&](int material) -> const PbrtMaterialDesc& { return *s.materials[size_t(material)].pbrt; };
  const PbrtMaterialDesc& def = pbrt_of(s.spheres[0].material);
  EXPECT_EQ(def.kind, PbrtMaterialKind::Diffuse);
  EXPECT_EQ(def.reflectance, Rgb(0.5f));

  const PbrtMaterialDesc& coated = pbrt_of(s.meshes[0].material);
  EXPECT_EQ(coated.kind, PbrtMaterialKind::CoatedDiffuse);
  expect_near(coated.reflectance.value, {0.1f, 0.2f, 0.3f});
  EXPECT_EQ(coated.uroughness, 0.05f);
  EXPECT_EQ(coated.vroughness, 0.05f);
  EXPECT_EQ(coated.thickness, 0.02f);
  EXPECT_EQ(coated.eta, 1.6f);
  EXPECT_EQ(coated.albedo, Rgb(0.1f));
  EXPECT_EQ(coated.g, 0.3f);
  EXPECT_EQ(coated.max_depth, 4);
  EXPECT_EQ(coated.n_samples, 2);
  EXPECT_TRUE(coated.remap_roughness);
  EXPECT_FALSE(s.materials[size_t(s.meshes[0].material)].brdf);

  const PbrtMaterialDesc& gold = pbrt_of(s.meshes[1].material);
  EXPECT_EQ(gold.kind, PbrtMaterialKind::Conductor);
  ASSERT_FALSE(gold.conductor_eta.textured() || gold.conductor_k.textured());
  const RgbComplexIor au = *named_conductor_ior("Au");  // eta and k reduced together
  EXPECT_EQ(gold.conductor_eta.value, au.eta);
  EXPECT_EQ(gold.conductor_k.value, au.k);
  expect_gold(gold.conductor_eta.value, gold.conductor_k.value);
  EXPECT_EQ(gold.uroughness, 0.1f);
  EXPECT_EQ(gold.vroughness, 0.2f);
  EXPECT_FALSE(gold.remap_roughness);
  EXPECT_FALSE(gold.conductor_by_reflectance);

  const PbrtMaterialDesc& glass = pbrt_of(s.meshes[2].material);
  EXPECT_EQ(glass.kind, PbrtMaterialKind::Dielectric);
  EXPECT_EQ(glass.eta, 1.33f);
  EXPECT_EQ(glass.uroughness, 0.3f);  // from the constant float texture
  EXPECT_EQ(pbrt_of(s.meshes[3].material).kind, PbrtMaterialKind::Interface);
}

TEST_F(PbrtAllDirectives, Lights) {
  const MeshDesc& emitter = s.meshes[4];
  ASSERT_TRUE(emitter.emission);
  EXPECT_TRUE(emitter.two_sided_emission);
  EXPECT_NEAR(emitter.emission->luminance(), 3.0f, 2e-3f);              // a blackbody of luminance 1, scaled by 3
  EXPECT_NEAR(emitter.emission->r / emitter.emission->b, 1.0f, 0.08f);  // 6500 K is near white
  EXPECT_EQ(*s.spheres[1].emission, Rgb(1, 2, 3));
  ASSERT_EQ(s.point_lights.size(), 1u);
  expect_near(s.point_lights[0].position, {1, 2, 3});
  EXPECT_EQ(s.point_lights[0].intensity, Rgb(2.0f));
  ASSERT_EQ(s.spot_lights.size(), 1u);
  const SpotLightDesc& spot = s.spot_lights[0];
  expect_near(spot.position, {0, 0, 1});
  expect_near(spot.direction, {0, 0, -1});
  EXPECT_EQ(spot.coverage_deg, 80.0f);
  EXPECT_EQ(spot.falloff_deg, 60.0f);
  EXPECT_EQ(spot.falloff, SpotFalloff::SmoothStep);
  EXPECT_EQ(spot.intensity, Rgb(5.0f));
  ASSERT_EQ(s.directional_lights.size(), 1u);
  expect_near(s.directional_lights[0].direction, {0, -1, 0});
  EXPECT_EQ(s.directional_lights[0].radiance, Rgb(3.0f));
  ASSERT_EQ(s.infinite_lights.size(), 1u);
  EXPECT_EQ(s.infinite_lights[0].radiance, Rgb(0.1f, 0.2f, 0.3f));
  for (const std::string& u : s.unsupported) EXPECT_EQ(u.find("infinite"), std::string::npos) << u;
}

// ---- lights' pbrt conventions ----

TEST(PbrtLights, PowerAndIlluminanceAsPbrtNormalisesThem) {
  const SceneDesc s =
      parse(kHead +
            "LightSource \"point\" \"rgb I\" [1 1 1] \"float power\" 100\n"
            "LightSource \"spot\" \"float coneangle\" 30 \"float conedeltaangle\" 10 \"float power\" 100\n"
            "LightSource \"distant\" \"float illuminance\" 7\n"
            "LightSource \"infinite\" \"float illuminance\" 3\n");
  EXPECT_NEAR(s.point_lights[0].intensity.g, 100.0f / (4.0f * kPi), 1e-4f);
  const float cos_end = std::cos(radians(30.0f)), cos_start = std::cos(radians(20.0f));
  EXPECT_NEAR(s.spot_lights[0].intensity.g, 100.0f / (2.0f * kPi * ((1.0f - cos_start) + 0.5f * (cos_start - cos_end))),
              1e-3f);
  EXPECT_EQ(s.directional_lights[0].radiance, Rgb(7.0f));
  expect_near(s.directional_lights[0].direction, {0, 0, 1});  // from (0,0,0) to (0,0,1)
  EXPECT_NEAR(s.infinite_lights[0].radiance.g, 3.0f / kPi, 1e-6f);
}

TEST(PbrtLights, RgbIlluminantsAreTakenAsWrittenAndSpectraNormalisedToLuminanceOne) {
  const SceneDesc s = parse(
      kHead +
      "AttributeBegin\nAreaLightSource \"diffuse\"\nShape \"sphere\"\nAttributeEnd\n"
      "AttributeBegin\nAreaLightSource \"diffuse\" \"spectrum L\" \"stdillum-D65\" \"float scale\" 2\n"
      "Shape \"sphere\"\nAttributeEnd\n"
      "AttributeBegin\nAreaLightSource \"diffuse\" \"spectrum L\" [300 5 800 5]\nShape \"sphere\"\nAttributeEnd\n");
  EXPECT_EQ(*s.spheres[0].emission, Rgb(1.0f));  // pbrt's default L: the colour space's illuminant, RGB 1
  EXPECT_EQ(*s.spheres[1].emission, Rgb(2.0f));
  EXPECT_NEAR(s.spheres[2].emission->luminance(), 1.0f, 1e-3f);  // a flat spectrum: luminance 1 whatever its level
}

TEST(PbrtLights, ReverseOrientationAndMirrorsTurnTheEmittingSide) {
  const std::string tri = "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n";
  const SceneDesc s =
      parse(kHead + "AreaLightSource \"diffuse\"\n" + tri + "AttributeBegin\nReverseOrientation\n" + tri +
            "AttributeEnd\n"
            "AttributeBegin\nScale 1 1 -1\n" +
            tri +
            "AttributeEnd\n"
            "AttributeBegin\nScale 1 1 -1\nReverseOrientation\n" +
            tri +
            "AttributeEnd\n"
            "AttributeBegin\nReverseOrientation\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] "
            "\"normal N\" [0 0 1 0 0 1 0 0 1]\nAttributeEnd\n"
            "AttributeBegin\nReverseOrientation\nShape \"sphere\"\nAttributeEnd\n");
  ASSERT_EQ(s.meshes.size(), 5u);
  const std::vector<uint32_t> as_written{0, 1, 2}, reversed{0, 2, 1};
  EXPECT_EQ(s.meshes[0].indices, as_written);
  EXPECT_EQ(s.meshes[1].indices, reversed);
  EXPECT_EQ(s.meshes[2].indices, reversed);    // a mirror flips the side
  EXPECT_EQ(s.meshes[3].indices, as_written);  // mirror and ReverseOrientation cancel
  // With normals the emitting side follows N, negated by ReverseOrientation: -z, so the winding turns.
  EXPECT_EQ(s.meshes[4].indices, reversed);
  expect_near(s.meshes[4].normals[0], {0, 0, -1});
  // An inward-facing sphere light cannot be rendered: it is dark and warned.
  EXPECT_FALSE(s.spheres[0].emission);
  EXPECT_TRUE(has_warning(s, "facing inwards")) << all_warnings(s);
}

// ---- instancing, includes, meshes from files ----

TEST(PbrtInstancing, ObjectInstancesShareOnePrototype) {
  const SceneDesc s = load_pbrt(kData + "instancing.pbrt");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_FALSE(s.meshes[0].visible);
  EXPECT_TRUE(s.meshes[0].is_instance_base);
  ASSERT_EQ(s.instances.size(), 3u);
  const Vec3f corner{0.5f, -0.5f, 0.0f};
  expect_near(s.instances[0].to_world.point(corner), {-2.5f, -0.5f, -1});
  expect_near(s.instances[1].to_world.point(corner), {0.5f, -0.5f, -1});
  expect_near(s.instances[2].to_world.point(corner), {4, -1, -2});
  for (const InstanceDesc& i : s.instances) EXPECT_EQ(i.material, s.meshes[0].material);
  ASSERT_EQ(s.spheres.size(), 3u);
  expect_near(s.spheres[2].to_world.point({0, 0, 0}), {3, 0, 0});
  expect_near(s.spheres[2].to_world.point({0.25f, 0, 0}), {3.5f, 0, 0});
}

TEST(PbrtIncludes, RelativeToTheIncludingFileThenTheMainFileImportIsScoped) {
  const SceneDesc s = load_pbrt(kData + "includes/main.pbrt");
  ASSERT_EQ(s.meshes.size(), 7u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(s.meshes[size_t(i)].positions[0].z, float(i + 1)) << i;
  const auto kind = [&](int m) { return s.materials[size_t(s.meshes[size_t(m)].material)].pbrt->kind; };
  EXPECT_EQ(kind(0), PbrtMaterialKind::Diffuse);
  EXPECT_EQ(kind(3), PbrtMaterialKind::Conductor);                   // set inside the imported file
  EXPECT_EQ(s.meshes[3].indices, (std::vector<uint32_t>{0, 2, 1}));  // its ReverseOrientation
  EXPECT_EQ(kind(4), PbrtMaterialKind::Diffuse);                     // ... neither leaks out of it
  EXPECT_EQ(s.meshes[4].indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(s.meshes[5].indices.size(), 6u);  // mesh.ply: a quad, fanned
  EXPECT_EQ(s.meshes[6].indices.size(), 3u);  // mesh.ply.gz
  EXPECT_EQ(s.meshes[6].normals.size(), 3u);
  EXPECT_TRUE(s.warnings.empty()) << all_warnings(s);
}

TEST(PbrtIncludes, GzippedIncludesAndScenesAndIncludeCycles) {
  const std::string dir = tmp("gz");
  write(dir + "/part.pbrt.gz", gzip("Shape \"sphere\" \"float radius\" 3\n"));
  write(dir + "/scene.pbrt.gz", gzip(kHead + "Include \"part.pbrt.gz\"\n"));
  const SceneDesc s = load_scene(dir + "/scene.pbrt.gz");
  ASSERT_EQ(s.spheres.size(), 1u);
  EXPECT_EQ(s.spheres[0].radius, 3.0f);
  write(dir + "/loop.pbrt", "Include \"loop.pbrt\"\n");
  const std::string e = error_of(kHead + "Include \"loop.pbrt\"\n", dir + "/main.pbrt");
  EXPECT_NE(e.find("nest deeper than"), std::string::npos) << e;
  write(dir + "/broken.ply.gz", "not gzip at all");
  EXPECT_NE(
      error_of(kHead + "Shape \"plymesh\" \"string filename\" \"broken.ply.gz\"\n", dir + "/main.pbrt").find("gzip"),
      std::string::npos);
}

// ---- shapes ----

TEST(PbrtShapes, BilinearPatchesAndLoopSubdivisionThroughLoadScene) {
  const SceneDesc s = parse(kHead +
                            "Shape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0  0 0 1 1 0 1 0 1 1 1 1 1] "
                            "\"integer indices\" [0 1 2 3 4 5 6 7]\n");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 3, 0, 3, 2, 4, 5, 7, 4, 7, 6}));
  const Vec3f n =
      cross(s.meshes[0].positions[1] - s.meshes[0].positions[0], s.meshes[0].positions[3] - s.meshes[0].positions[0]);
  EXPECT_GT(n.z, 0.0f);  // pbrt's patch normal: (p10 - p00) x (p01 - p00)
  // loopsubdiv is subdivided by load_scene like any marked mesh (and --subdivide overrides it).
  const std::string dir = tmp("loop");
  write(dir + "/tet.pbrt", kHead +
                               "Shape \"loopsubdiv\" \"integer levels\" 2 \"point3 P\" [0 0 0 1 0 0 0 1 0 0 0 1] "
                               "\"integer indices\" [0 2 1 0 1 3 0 3 2 1 2 3]\n");
  EXPECT_EQ(load_scene(dir + "/tet.pbrt").meshes[0].indices.size(), 4u * 16u * 3u);
  LoadOptions lo;
  lo.subdivide = 1;
  EXPECT_EQ(load_scene(dir + "/tet.pbrt", lo).meshes[0].indices.size(), 4u * 4u * 3u);
}

// ---- warnings ----

TEST(PbrtWarnings, EveryUnsupportedFeatureIsNamedWithFileAndLine) {
  const SceneDesc s = load_pbrt(kData + "unsupported.pbrt");
  const std::string f = "unsupported.pbrt: ";
  const std::pair<std::string, std::string> expected[] = {
      {f + "line 5 (Film \"gbuffer\")", "AOV layers"},
      {f + "line 6 (PixelFilter \"sinc\")", "not supported"},
      {f + "line 7 (Integrator \"bdpt\")", "Kiln's path tracer"},
      {f + "line 7 (Integrator \"bdpt\")", "\"regularize\" is ignored"},
      {f + "line 8 (Accelerator)", "Kiln traces rays"},
      {f + "line 10 (MakeNamedMedium \"puff\")", "\"float puffiness\" is not used"},
      {f + "line 11 (Texture \"checks\")", "ptex textures are not rendered"},
      {f + "line 12 (Material \"diffuse\")", "texture \"checks\""},
      {f + "line 13 (Shape \"trianglemesh\")", "\"float bogus\" is not used"},
      {f + "line 14 (Material \"hair\")", "not supported"},
      {f + "line 15 (Shape \"curve\")", "not supported"},
      {f + "line 16 (Shape \"cone\")", "pbrt-v3 shape"},
      {f + "line 17 (LightSource \"projection\")", "not supported"},
      {f + "line 18 (Shape \"bilinearmesh\")", "not planar"},
      {f + "line 19 (LightSource \"goniometric\")", "not supported"},
      {f + "line 21 (AreaLightSource \"diffuse\")", "\"power\" is not supported"},
      {f + "line 28 (TransformBegin)", "deprecated"},
      {f + "line 30 (WorldEnd)", "pbrt-v3 syntax"},
  };
  for (const auto& [where, what] : expected)
    EXPECT_TRUE(has_warning(s, where, what)) << where << " " << what << "\n" << all_warnings(s);
  EXPECT_EQ(s.warnings.size(), std::size(expected)) << all_warnings(s);
  for (const char* feature : {"ptex textures", "pbrt shape \"curve\""}) {
    bool found = false;
    for (const std::string& u : s.unsupported) found |= u.find(feature) != std::string::npos;
    EXPECT_TRUE(found) << feature;
  }
  // The procedural cloud is rendered: its medium is read, only the parameter it does not know is warned.
  for (const std::string& u : s.unsupported) EXPECT_EQ(u.find("cloud"), std::string::npos) << u;
  ASSERT_EQ(s.media.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<CloudMediumDesc>(s.media[0].params));
}

// ---- spectra ----

TEST(PbrtSpectrum, BlackbodyChromaticityFollowsThePlanckianLocus) {
  // CIE 1931 chromaticities of blackbodies (Planckian locus): 2856 K (illuminant A) and 6500 K.
  const struct { float kelvin, x, y; } locus[] = {{2856.0f, 0.4476f, 0.4074f}, {6500.0f, 0.3135f, 0.3236f}};
  for (const auto& p : locus) {
    const Vec3f xyz = blackbody_xyz(p.kelvin);
    const float sum = xyz.x + xyz.y + xyz.z;
    EXPECT_NEAR(xyz.x / sum, p.x, 3e-3f) << p.kelvin;
    EXPECT_NEAR(xyz.y / sum, p.y, 3e-3f) << p.kelvin;
  }
  const Rgb d65 = *named_spectrum_rgb("stdillum-D65", SpectrumUse::Illuminant);
  EXPECT_EQ(d65, Rgb(1.0f));
  EXPECT_NEAR(chromaticity_to_linear_srgb(0.3127f, 0.3290f).r, 1.0f, 2e-3f);  // D65's white point
  EXPECT_NEAR(chromaticity_to_linear_srgb(0.3127f, 0.3290f).b, 1.0f, 2e-3f);
  const std::vector<float> l{400, 700}, v{0.25f, 0.25f};
  expect_near(sampled_spectrum_rgb(l, v, SpectrumUse::Unbounded), Rgb(0.25f));
  const std::vector<float> l2{360, 830}, v2{0.4f, 0.4f};
  expect_near(sampled_spectrum_rgb(l2, v2, SpectrumUse::Albedo), Rgb(0.4f), 1e-4f);
}

// pbrt's named spectra against values published independently of Kiln's table: the CIE chromaticities of the
// standard illuminants (back from RGB through the sRGB matrix of IEC 61966-2-1; D50 as pbrt-v4 tabulates it, whose
// table integrates to x 0.3368 against the CIE 1931 tables instead of the published 0.3457), illuminant A as
// Planck's law at 2856 K (its definition), N-BK7 from its Sellmeier formula, gold's measured reflectance.
TEST(PbrtSpectrum, NamedSpectraMatchPublishedValues) {
  const struct { const char* name; double x, y; } illuminants[] = {{"stdillum-D65", 0.31271, 0.32902},
                                                                  {"stdillum-D50", 0.33681, 0.35798},
                                                                  {"stdillum-A", 0.44757, 0.40745},
                                                                  {"illum-acesD60", 0.32168, 0.33767}};
  for (const auto& il : illuminants) {
    const Rgb c = *named_spectrum_rgb(il.name, SpectrumUse::Illuminant);
    const double X = 0.4124 * c.r + 0.3576 * c.g + 0.1805 * c.b, Y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b,
                 Z = 0.0193 * c.r + 0.1192 * c.g + 0.9505 * c.b;
    EXPECT_NEAR(Y, 1.0, 1e-3) << il.name << ": an illuminant has luminance 1";
    EXPECT_NEAR(X / (X + Y + Z), il.x, 5e-4) << il.name;
    EXPECT_NEAR(Y / (X + Y + Z), il.y, 5e-4) << il.name;
  }
  expect_near(*named_spectrum_rgb("stdillum-A", SpectrumUse::Illuminant), *blackbody_rgb(2856.0f), 0.02f);

  // An index reduced D65-lit: its green channel is the index near the e line (546.1 nm), where D65 times y-bar
  // peaks; BK7 by its Sellmeier formula there, every glass between its own indices at the d (587.6 nm) and F
  // (486.1 nm) lines. (pbrt-v4's "glass-F5" holds Schott SF5's data.)
  const auto bk7 = [](double um) {
    const double l2 = um * um;
    return std::sqrt(1 + 1.03961212 * l2 / (l2 - 0.00600069867) + 0.231792344 * l2 / (l2 - 0.0200179144) +
                     1.01046945 * l2 / (l2 - 103.560653));
  };
  EXPECT_NEAR(named_spectrum_rgb("glass-BK7", SpectrumUse::Unbounded)->g, bk7(0.546074), 3e-4);
  for (const char* glass : {"glass-BK7", "glass-BAF10", "glass-FK51A", "glass-LASF9", "glass-F5", "glass-F10",
                            "glass-F11"}) {
    const PiecewiseSpectrum n = *named_spectrum(glass);
    const float g = named_spectrum_rgb(glass, SpectrumUse::Unbounded)->g;
    EXPECT_GT(g, n(587.6f)) << glass;
    EXPECT_LT(g, n(486.1f)) << glass;
  }
  expect_gold(*named_spectrum_rgb("metal-Au-eta", SpectrumUse::Unbounded),
              *named_spectrum_rgb("metal-Au-k", SpectrumUse::Unbounded));
}

// ---- the pbrt-v4 killeroo scene (shared data) ----

TEST(PbrtKilleroo, SimpleSceneLoads) {
  const std::string path = std::string(KILN_SHARED_DIR) + "/scenes/pbrt/killeroos/killeroo-simple.pbrt";
  KILN_NEED_SHARED_PATH(path);
  LoadOptions lo;
  lo.defer_subdivision = true;
  const SceneDesc s = load_scene(path, lo);
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].width, 700);
  EXPECT_EQ(s.cameras[0].num_samples, 256);
  EXPECT_EQ(s.cameras[0].image_name, "killeroo-simple.exr");
  ASSERT_EQ(s.spheres.size(), 1u);
  EXPECT_EQ(*s.spheres[0].emission, Rgb(2000.0f));
  EXPECT_EQ(s.spheres[0].radius, 3.0f);
  ASSERT_EQ(s.meshes.size(), 4u);
  EXPECT_EQ(s.meshes[2].subdivide, 1);
  EXPECT_EQ(s.meshes[3].subdivide, 1);
  EXPECT_EQ(s.materials[size_t(s.meshes[2].material)].pbrt->kind, PbrtMaterialKind::CoatedDiffuse);
  EXPECT_EQ(s.materials[size_t(s.meshes[0].material)].pbrt->reflectance, Rgb(0.5f, 0.5f, 0.8f));
  EXPECT_EQ(s.warnings.size(), 1u) << all_warnings(s);  // only the halton sampler
}

}  // namespace
}  // namespace kiln
