// CS171 GI JSON configs: mapping to SceneDesc (camera, light quad, materials, objects) and errors naming the file
// and key path. Error cases are variants of one small config written to KILN_TEST_TMP.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "core/error.h"
#include "scenes/json_loader.h"
#include "scenes/material_mapping.h"
#include "support/shared_data.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

const std::string kObjData = std::string(KILN_SOURCE_DIR) + "/tests/data/obj/";

// Every key the format has; materials of all three types; two objects sharing one OBJ.
const std::string kBase = R"({
  "spp": 4,
  "max_depth": 3,
  "image_resolution": [8, 6],
  "cam_config": {"position": [0, 1, 6.8], "look_at": [0, 1, 0], "ref_up": [0, 1, 0],
                 "vertical_fov": 19.5, "focal_length": 1},
  "light_config": {"position": [0, 1.98, 0], "size": [0.5, 0.25], "radiance": [17, 12, 5]},
  "materials": [
    {"name": "grey", "type": "diffuse", "color": [0.725, 0.71, 0.68]},
    {"name": "chrome", "type": "specular", "color": [0.9, 0.8, 0.7]},
    {"name": "glass", "type": "translucent", "color": [1, 1, 1], "ior": 1.33}
  ],
  "objects": [
    {"obj_file_path": "QUAD", "material_name": "grey", "translate": [1, 2, 3], "scale": 2, "has_bvh": false},
    {"obj_file_path": "QUAD", "material_name": "glass", "translate": [0, 0, 0], "scale": 1, "has_bvh": true}
  ]
})";

// Replaces every occurrence of from; fails the test when there is none (a stale mutation would test nothing).
std::string with(std::string text, const std::string& from, const std::string& to) {
  size_t pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "mutation target not in config: " << from;
  for (; pos != std::string::npos; pos = text.find(from, pos + to.size())) text.replace(pos, from.size(), to);
  return text;
}

// Writes the config as <tmp>/<test name>.json, with QUAD replaced by an absolute OBJ path.
std::string write_config(const std::string& text) {
  const fs::path dir = fs::path(KILN_TEST_TMP) / "cs171_json";
  fs::create_directories(dir);
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "_" + info->name();
  for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  const fs::path path = dir / (name + ".json");
  std::string body = text;
  for (size_t pos; (pos = body.find("\"QUAD\"")) != std::string::npos;)
    body.replace(pos, 6, "\"" + kObjData + "quad_no_normals.obj\"");
  std::ofstream(path) << body;
  return path.string();
}

std::string error_of(const std::string& config_text) {
  const std::string path = write_config(config_text);
  try {
    load_cs171_json(path);
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << "message does not start with the file: " << msg;
    return msg;
  }
  ADD_FAILURE() << "no kiln::Error for:\n" << config_text;
  return {};
}

// Expects the config to fail with "FILE: key_path: ..." containing detail.
void expect_error(const std::string& config_text, const std::string& key_path, const std::string& detail) {
  const std::string msg = error_of(config_text);
  EXPECT_NE(msg.find(": " + key_path + ": "), std::string::npos) << "key path " << key_path << " not in: " << msg;
  EXPECT_NE(msg.find(detail), std::string::npos) << "'" << detail << "' not in: " << msg;
}

Vec3f tri_normal(const MeshDesc& m, int t) {
  const Vec3f p0 = m.positions[m.indices[3 * t]], p1 = m.positions[m.indices[3 * t + 1]],
              p2 = m.positions[m.indices[3 * t + 2]];
  return cross(p1 - p0, p2 - p0);
}

TEST(Cs171Json, BaseConfigMapsToSceneDesc) {
  const std::string path = write_config(kBase);
  const SceneDesc s = load_cs171_json(path);
  EXPECT_EQ(s.format, "cs171-json");
  EXPECT_EQ(s.source_path, path);
  EXPECT_TRUE(s.png_gamma_encode);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_TRUE(s.max_recursion_depth.has_value());
  EXPECT_EQ(*s.max_recursion_depth, 3);  // vertices that gather direct light = Kiln bounces

  ASSERT_EQ(s.cameras.size(), 1u);
  const CameraDesc& c = s.cameras[0];
  EXPECT_EQ(c.position, Vec3f(0, 1, 6.8f));
  EXPECT_EQ(c.gaze, Vec3f(0, 0, -1));
  EXPECT_EQ(c.up, Vec3f(0, 1, 0));
  EXPECT_TRUE(c.use_fov);
  EXPECT_NEAR(c.fov_y_deg, 19.5f, 1e-4f);
  EXPECT_EQ(c.width, 8);
  EXPECT_EQ(c.height, 6);
  EXPECT_EQ(c.num_samples, 4);
  EXPECT_EQ(c.image_name, "Cs171Json_BaseConfigMapsToSceneDesc.exr");
  EXPECT_EQ(c.renderer, RendererKind::PathTracing);
  EXPECT_TRUE(c.renderer_explicit);
  EXPECT_TRUE(c.pt.next_event_estimation);
  EXPECT_TRUE(c.pt.importance_sampling);
  EXPECT_FALSE(c.pt.russian_roulette);
  EXPECT_FALSE(c.tonemap.has_value());
  EXPECT_EQ(c.aperture_size, 0.0f);

  ASSERT_EQ(s.brdfs.size(), 1u);
  EXPECT_EQ(s.brdfs[0].kind, BrdfKind::Lambert);
  ASSERT_EQ(s.materials.size(), 4u);  // three from the file + the light's black material
  EXPECT_EQ(s.materials[0].type, MaterialType::Plain);
  EXPECT_EQ(s.materials[0].brdf, std::optional<int>(0));
  EXPECT_EQ(s.materials[0].diffuse, Rgb(0.725f, 0.71f, 0.68f));
  EXPECT_EQ(s.materials[1].type, MaterialType::Mirror);
  EXPECT_EQ(s.materials[1].mirror, Rgb(0.9f, 0.8f, 0.7f));
  EXPECT_TRUE(s.materials[1].diffuse.is_black());
  EXPECT_EQ(s.materials[2].type, MaterialType::Dielectric);
  EXPECT_FLOAT_EQ(s.materials[2].refraction_index, 1.33f);
  EXPECT_TRUE(s.materials[2].has_refraction_index);
  EXPECT_EQ(s.materials[3].type, MaterialType::Plain);
  EXPECT_TRUE(s.materials[3].diffuse.is_black());

  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.meshes[0].material, 0);
  EXPECT_EQ(s.meshes[1].material, 2);
  EXPECT_EQ(s.meshes[0].name, "objects[0] (quad_no_normals.obj)");
  EXPECT_FALSE(s.meshes[0].emission.has_value());
  // translate after uniform scale: (1, 1, 0) -> 2 * (1, 1, 0) + (1, 2, 3)
  EXPECT_EQ(s.meshes[0].to_world.point(Vec3f(1, 1, 0)), Vec3f(3, 4, 3));
  EXPECT_TRUE(s.meshes[1].to_world.is_identity());
  EXPECT_TRUE(s.area_lights.empty());
  EXPECT_TRUE(s.point_lights.empty());
}

TEST(Cs171Json, LightIsADownFacingEmissiveQuad) {
  const SceneDesc s = load_cs171_json(write_config(kBase));
  const MeshDesc& light = s.meshes.back();
  ASSERT_TRUE(light.emission.has_value());
  EXPECT_EQ(*light.emission, Rgb(17, 12, 5));
  EXPECT_EQ(light.material, 3);
  EXPECT_TRUE(light.to_world.is_identity());
  EXPECT_TRUE(light.normals.empty());
  ASSERT_EQ(light.indices.size(), 6u);
  float area = 0;
  for (int t = 0; t < 2; ++t) {
    const Vec3f n = tri_normal(light, t);
    EXPECT_EQ(n.x, 0.0f);
    EXPECT_EQ(n.z, 0.0f);
    EXPECT_LT(n.y, 0.0f) << "triangle " << t << " does not face down";
    area += 0.5f * length(n);
  }
  EXPECT_FLOAT_EQ(area, 0.5f * 0.25f);
  Vec3f lo(kInfinity), hi(-kInfinity);
  for (const Vec3f& p : light.positions) lo = min(lo, p), hi = max(hi, p);
  EXPECT_EQ(lo, Vec3f(-0.25f, 1.98f, -0.125f));  // size is the full extent along x, then z
  EXPECT_EQ(hi, Vec3f(0.25f, 1.98f, 0.125f));
}

// The descriptions build the materials the CS171 framework has: Lambert, ideal mirror, glass, and a light that
// neither reflects nor transmits.
TEST(Cs171Json, MaterialsBuildToLambertMirrorDielectricAndBlack) {
  const SceneDesc s = load_cs171_json(write_config(kBase));
  const Material grey = build_material(s.materials[0], s);
  ASSERT_TRUE(std::holds_alternative<Lambert>(grey.surface));
  EXPECT_FALSE(grey.has_delta());
  const Material chrome = build_material(s.materials[1], s);
  EXPECT_FALSE(chrome.has_surface());
  EXPECT_TRUE(std::holds_alternative<Mirror>(chrome.delta));
  const Material glass = build_material(s.materials[2], s);
  EXPECT_FALSE(glass.has_surface());
  EXPECT_TRUE(std::holds_alternative<Dielectric>(glass.delta));
  EXPECT_TRUE(glass.absorption.is_black());
  const Material light = build_material(s.materials[3], s);
  EXPECT_FALSE(light.has_surface());
  EXPECT_FALSE(light.has_delta());
}

TEST(Cs171Json, FocalLengthScalesTheImagePlane) {
  const SceneDesc s = load_cs171_json(write_config(with(kBase, "\"focal_length\": 1", "\"focal_length\": 2")));
  const float expected = 2.0f * std::atan(2.0f * std::tan(radians(19.5f) / 2.0f));
  EXPECT_NEAR(radians(s.cameras[0].fov_y_deg), expected, 1e-6f);
}

TEST(Cs171Json, CameraBasisFromLookAt) {
  const SceneDesc s = load_cs171_json(write_config(with(
      with(kBase, "\"look_at\": [0, 1, 0]", "\"look_at\": [3, 1, 6.8]"), "\"ref_up\": [0, 1, 0]",
      "\"ref_up\": [0, 2, 0.5]")));
  EXPECT_EQ(s.cameras[0].gaze, Vec3f(1, 0, 0));
  EXPECT_NEAR(length(s.cameras[0].up), 1.0f, 1e-6f);
}

TEST(Cs171Json, MaterialDefaults) {
  std::string cfg = with(kBase, R"("color": [0.9, 0.8, 0.7])", R"("name2": 0)");
  cfg = with(cfg, R"(, "ior": 1.33)", "");
  const SceneDesc s = load_cs171_json(write_config(cfg));
  EXPECT_EQ(s.materials[1].mirror, Rgb(1.0f));  // specular without colour: a perfect mirror
  EXPECT_FLOAT_EQ(s.materials[2].refraction_index, 1.5f);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find(": materials[1].name2: unknown key"), std::string::npos) << s.warnings[0];
}

TEST(Cs171Json, UnknownKeysAndExtraElementsAreWarnedWithTheirPath) {
  std::string cfg = with(kBase, "\"spp\": 4,", "\"spp\": 4, \"exposure\": 2,");
  cfg = with(cfg, "\"focal_length\": 1}", "\"focal_length\": 1, \"aperture\": 0.1}");
  cfg = with(cfg, "\"scale\": 2,", "\"scale\": 2, \"rotate\": [0, 1, 0],");
  cfg = with(cfg, "\"translate\": [1, 2, 3]", "\"translate\": [1, 2, 3, 4]");
  cfg = with(cfg, "\"radiance\": [17, 12, 5]}", "\"radiance\": [17, 12, 5], \"normal\": [0, -1, 0]}");
  cfg = with(cfg, R"("type": "diffuse",)", R"("type": "diffuse", "roughness": 0.5,)");
  cfg = with(cfg, R"("color": [1, 1, 1])", R"("color": [1, 0.5, 1])");
  const std::string path = write_config(cfg);
  const SceneDesc s = load_cs171_json(path);
  const std::string expected[] = {
      "exposure: unknown key",         "cam_config.aperture: unknown key",
      "light_config.normal: unknown key", "materials[0].roughness: unknown key",
      "objects[0].rotate: unknown key", "objects[0].translate: has 4 elements; only the first 3 are used",
      "materials[2].color: tint of a translucent material is ignored"};
  EXPECT_EQ(s.warnings.size(), std::size(expected));
  for (const std::string& e : expected) {
    bool found = false;
    for (const std::string& w : s.warnings) found = found || w.rfind(path + ": " + e, 0) == 0;
    EXPECT_TRUE(found) << "no warning starting with '" << path << ": " << e << "'";
  }
}

TEST(Cs171Json, IntegralFloatsAreIntegers) {
  const SceneDesc s = load_cs171_json(write_config(with(kBase, "\"spp\": 4", "\"spp\": 4.0")));
  EXPECT_EQ(s.cameras[0].num_samples, 4);
}

TEST(Cs171Json, MissingRequiredKeysAreErrors) {
  const struct {
    const char* from;
    const char* to;
    const char* key_path;
  } cases[] = {
      {"\"spp\": 4,", "", "spp"},
      {"\"max_depth\": 3,", "", "max_depth"},
      {"\"image_resolution\": [8, 6],", "", "image_resolution"},
      {"\"vertical_fov\": 19.5,", "", "cam_config.vertical_fov"},
      {", \"focal_length\": 1", "", "cam_config.focal_length"},
      {", \"radiance\": [17, 12, 5]", "", "light_config.radiance"},
      {"\"position\": [0, 1.98, 0], ", "", "light_config.position"},
      {R"("color": [0.725, 0.71, 0.68])", R"("x": 1)", "materials[0].color"},
      {R"("name": "chrome", )", "", "materials[1].name"},
      {R"(, "has_bvh": true)", "", "objects[1].has_bvh"},
      {R"("translate": [1, 2, 3], )", "", "objects[0].translate"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.key_path);
    expect_error(with(kBase, c.from, c.to), c.key_path, "missing required key");
  }
  // Whole sections.
  for (const char* section : {"cam_config", "light_config", "materials", "objects"}) {
    SCOPED_TRACE(section);
    std::string cfg = with(kBase, std::string("\"") + section + "\"", std::string("\"old_") + section + "\"");
    expect_error(cfg, section, "missing required key");
  }
}

TEST(Cs171Json, WrongTypesAreErrors) {
  const struct {
    const char* from;
    const char* to;
    const char* key_path;
    const char* detail;
  } cases[] = {
      {"\"spp\": 4", "\"spp\": \"4\"", "spp", "expected an integer, got string"},
      {"\"spp\": 4", "\"spp\": 4.5", "spp", "expected an integer, got 4.5"},
      {"\"spp\": 4", "\"spp\": 0", "spp", "must be greater than 0"},
      {"\"max_depth\": 3", "\"max_depth\": 0", "max_depth", "must be at least 1"},
      {"[8, 6]", "[8]", "image_resolution", "expected 2 elements, got 1"},
      {"[8, 6]", "[8, -6]", "image_resolution[1]", "height must be greater than 0"},
      {"[8, 6]", "\"8x6\"", "image_resolution", "expected an array, got string"},
      {"\"vertical_fov\": 19.5", "\"vertical_fov\": 180", "cam_config.vertical_fov", "below 180"},
      {"\"focal_length\": 1", "\"focal_length\": 0", "cam_config.focal_length", "greater than 0"},
      {"\"ref_up\": [0, 1, 0]", "\"ref_up\": [0, 0, 2]", "cam_config.ref_up", "parallel to the view direction"},
      {"\"look_at\": [0, 1, 0]", "\"look_at\": [0, 1, 6.8]", "cam_config.look_at", "equals cam_config.position"},
      {"\"position\": [0, 1, 6.8]", "\"position\": [0, \"1\", 6.8]", "cam_config.position[1]",
       "expected a number, got string"},
      {"\"size\": [0.5, 0.25]", "\"size\": [0.5, 0]", "light_config.size[1]", "greater than 0"},
      {"\"radiance\": [17, 12, 5]", "\"radiance\": [17, -12, 5]", "light_config.radiance", "must not be negative"},
      {"\"has_bvh\": false", "\"has_bvh\": 0", "objects[0].has_bvh", "expected true or false, got number"},
      {"\"scale\": 2", "\"scale\": -2", "objects[0].scale", "greater than 0"},
      {"\"scale\": 2", "\"scale\": [2, 2, 2]", "objects[0].scale", "expected a number, got array"},
      {"\"translate\": [1, 2, 3]", "\"translate\": [1, 2]", "objects[0].translate", "expected 3 elements, got 2"},
      {R"("material_name": "grey")", R"("material_name": null)", "objects[0].material_name",
       "expected a string, got null"},
      {R"("ior": 1.33)", R"("ior": -1)", "materials[2].ior", "greater than 0"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.key_path);
    expect_error(with(kBase, c.from, c.to), c.key_path, c.detail);
  }
  expect_error(with(with(kBase, "\"cam_config\": {", "\"cam_config\": [{"), "\"focal_length\": 1}",
                    "\"focal_length\": 1}]"),
               "cam_config", "expected an object, got array");
  expect_error(with(kBase, "\"grey\", \"translate\"", "\"grey\", \"translate\": null, \"t\""), "objects[0].translate",
               "expected an array, got null");
}

TEST(Cs171Json, UnknownMaterialTypeIsAnError) {
  expect_error(with(kBase, R"("type": "translucent")", R"("type": "environment")"), "materials[2].type",
               "unknown material type 'environment'");
  expect_error(with(kBase, R"("type": "diffuse")", R"("type": "Diffuse")"), "materials[0].type",
               "unknown material type 'Diffuse'");
}

TEST(Cs171Json, DanglingAndDuplicateMaterialNamesAreErrors) {
  expect_error(with(kBase, R"("material_name": "glass")", R"("material_name": "gold")"),
               "objects[1].material_name", "no material named 'gold' (defined: chrome, glass, grey)");
  expect_error(with(kBase, R"("name": "chrome")", R"("name": "grey")"), "materials[1].name",
               "duplicate material name 'grey'");
}

TEST(Cs171Json, UnloadableObjIsAnErrorNamingKeyAndObjFile) {
  const std::string msg = error_of(with(kBase, "\"QUAD\", \"material_name\": \"glass\"",
                                        "\"" + kObjData + "zero_index.obj\", \"material_name\": \"glass\""));
  EXPECT_NE(msg.find(": objects[1].obj_file_path: cannot load '"), std::string::npos) << msg;
  EXPECT_NE(msg.find("zero_index.obj: line 6: face index 0"), std::string::npos) << msg;
}

TEST(Cs171Json, FileErrors) {
  const std::string missing = std::string(KILN_TEST_TMP) + "/cs171_json/no_such_config.json";
  try {
    load_cs171_json(missing);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), missing + ": config file does not exist");
  }
  const std::string msg = error_of("{\n  \"spp\": 4,\n  \"max_depth\" 3\n}");
  EXPECT_NE(msg.find("invalid JSON: parse error at line 3, column"), std::string::npos) << msg;
  EXPECT_NE(error_of("[1, 2]").find("expected an object, got array"), std::string::npos);
}

TEST(Cs171Json, ObjPathsAreRelativeToTheConfig) {
  const std::string path = std::string(KILN_SOURCE_DIR) + "/tests/data/cs171/relative_paths.json";
  const SceneDesc s = load_cs171_json(path);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].positions.size(), 4u);
  EXPECT_GT(tri_normal(s.meshes[0], 0).y, 0.0f);  // oriented by its normals
  EXPECT_EQ(*s.max_recursion_depth, 5);
  EXPECT_EQ(s.cameras[0].image_name, "relative_paths.exr");
  EXPECT_EQ(s.cameras[0].width, 32);
  EXPECT_EQ(s.cameras[0].height, 24);
}

// ---- The staged course configs and the bundled copies.

void expect_cornell_box(const SceneDesc& s, size_t objects) {
  EXPECT_TRUE(s.warnings.empty());
  ASSERT_EQ(s.meshes.size(), objects + 1);
  ASSERT_EQ(s.materials.size(), 4u);
  EXPECT_EQ(s.materials[2].diffuse, Rgb(0.63f, 0.065f, 0.05f));  // red_diffuse
  EXPECT_EQ(s.meshes[0].material, 2);                              // left wall is red
  EXPECT_EQ(s.meshes[1].material, 1);                              // right wall is green
  const CameraDesc& c = s.cameras.at(0);
  EXPECT_EQ(c.width, 600);
  EXPECT_EQ(c.height, 600);
  EXPECT_EQ(c.num_samples, 256);
  EXPECT_NEAR(c.fov_y_deg, 19.5f, 1e-4f);
  EXPECT_EQ(*s.meshes.back().emission, Rgb(17, 12, 5));
  // Floor (objects[2]) faces up after orientation by its vn.
  EXPECT_GT(tri_normal(s.meshes[2], 0).y, 0.0f);
}

class Cs171SharedConfigs : public ::testing::Test {
 protected:
  void SetUp() override {
    KILN_NEED_SHARED_PATH(dir_);
  }
  const std::string dir_ = std::string(KILN_SHARED_DIR) + "/scenes/cs171/configs";
};

TEST_F(Cs171SharedConfigs, SimpleLoads) {
  const SceneDesc s = load_cs171_json(dir_ + "/simple.json");
  expect_cornell_box(s, 7);
  EXPECT_EQ(*s.max_recursion_depth, 12);
  EXPECT_EQ(s.cameras[0].image_name, "simple.exr");
  // short_box moved by (-0.7, 0, 0.6)
  EXPECT_EQ(s.meshes[5].to_world.point(Vec3f(0, 0, 0)), Vec3f(-0.7f, 0, 0.6f));
}

TEST_F(Cs171SharedConfigs, LargeMeshReportsTheMissingDragon) {
  const std::string path = dir_ + "/large_mesh.json";
  try {
    load_cs171_json(path);
    FAIL() << "large_mesh.json loaded although stanford_dragon.obj is not staged";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ": objects[5].obj_file_path: cannot load '../assets/stanford_dragon.obj': ", 0), 0u)
        << msg;
    EXPECT_NE(msg.find("stanford_dragon.obj: OBJ file does not exist"), std::string::npos) << msg;
  }
}

// Every staged config must be listed here with its expected outcome, so a new one cannot go untested.
TEST_F(Cs171SharedConfigs, EveryConfigLoadsOrFailsAsSpecified) {
  const std::map<std::string, std::string> expected_error = {{"simple.json", ""},
                                                              {"large_mesh.json", "stanford_dragon.obj"}};
  int seen = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    auto it = expected_error.find(name);
    ASSERT_NE(it, expected_error.end()) << "no expectation for staged config " << name;
    ++seen;
    std::string error;
    try {
      load_cs171_json(entry.path().string());
    } catch (const Error& e) {
      error = e.what();
    }
    if (it->second.empty())
      EXPECT_EQ(error, "") << name;
    else
      EXPECT_NE(error.find(it->second), std::string::npos) << name << ": " << error;
  }
  EXPECT_EQ(seen, static_cast<int>(expected_error.size()));
}

TEST(Cs171BundledConfigs, SimpleAndLargeMeshWithoutDragonLoad) {
  const std::string dir = std::string(KILN_SOURCE_DIR) + "/scenes/cs171/configs/";
  const SceneDesc simple = load_cs171_json(dir + "simple.json");
  expect_cornell_box(simple, 7);

  const SceneDesc large = load_cs171_json(dir + "large_mesh_no_dragon.json");
  expect_cornell_box(large, 7);
  EXPECT_EQ(*large.max_recursion_depth, 10);
  const MeshDesc& bunny = large.meshes[5];
  EXPECT_EQ(bunny.name, "objects[5] (stanford_bunny.obj)");
  EXPECT_EQ(bunny.indices.size(), 3u * 7361u);
  Vec3f lo(kInfinity), hi(-kInfinity);
  for (const Vec3f& p : bunny.positions) {
    const Vec3f w = bunny.to_world.point(p);
    lo = min(lo, w), hi = max(hi, w);
  }
  // Documented placement: x in [-0.78, -0.16], y in [0.03, 0.65], z in [-0.05, 0.43].
  EXPECT_NEAR(lo.x, -0.78f, 0.01f);
  EXPECT_NEAR(hi.x, -0.16f, 0.01f);
  EXPECT_NEAR(lo.y, 0.03f, 0.01f);
  EXPECT_NEAR(hi.y, 0.65f, 0.01f);
  EXPECT_NEAR(lo.z, -0.05f, 0.01f);
  EXPECT_NEAR(hi.z, 0.43f, 0.01f);
}

}  // namespace
}  // namespace kiln
