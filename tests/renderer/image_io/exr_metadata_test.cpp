// What `kiln render` writes into its EXR besides pixels: every kiln: metadata key with the values the command
// line implies, the channel names other tools look for, and the data window of a crop inside the full frame.
#include <gtest/gtest.h>

#include <cstdlib>

#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render/scene_fingerprint.h"

namespace kiln::test {
namespace {

int render(const std::string& args) {
  const std::string cmd = std::string(KILN_BINARY) + " render " + args + " -q > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string default_scene() { return std::string(KILN_SOURCE_DIR) + "/scenes/default.xml"; }

// Why: parts are merged, compared and audited by these keys; a key missing or carrying the wrong value breaks
// `kiln merge` and every report built on the metadata.
TEST(ExrMetadata, EveryKilnKeyChannelNamesAndTheCropDataWindow) {
  const std::string dir = tmp_dir("exr_metadata");
  ASSERT_EQ(render(default_scene() + " -o " + dir + " --spp 3 --seed 42 --crop 100,300,50,250 --aov depth"), 0);
  const ExrFile f = read_exr(dir + "/default.exr");
  SceneFingerprint fingerprint;
  load_scene_fingerprinted(default_scene(), {}, fingerprint);
  const std::pair<const char*, std::string> exact[] = {
      {"kiln:version", KILN_VERSION}, {"kiln:scene", default_scene()}, {"kiln:camera", "1"},
      {"kiln:spp", "3"},              {"kiln:spp_first", "0"},         {"kiln:spp_last", "3"},
      {"kiln:spp_total", "3"},        {"kiln:scene_files", scene_files_metadata(fingerprint)},       {"kiln:seed", "42"},
      {"kiln:rules", "Kiln's rules"},         {"kiln:incomplete", "false"}};
  for (const auto& [key, value] : exact) EXPECT_EQ(f.find(key), value) << key;
  // Keys whose values are computed: present and well formed.
  EXPECT_EQ(f.find("kiln:scene_hash"), fingerprint.hash);
  EXPECT_EQ(f.find("kiln:scene_files"), fingerprint.files.at(0).hash + " default.xml");
  EXPECT_NE(f.find("kiln:integrator").find("path"), std::string::npos) << f.find("kiln:integrator");
  EXPECT_NE(f.find("kiln:render_options").find("physical_lights=0"), std::string::npos) << f.find("kiln:render_options");
  EXPECT_GT(std::stod(f.find("kiln:render_seconds")), 0.0);
  EXPECT_FALSE(f.find("kiln:filter").empty());
  EXPECT_DOUBLE_EQ(std::stod(f.find("kiln:mean_spp")), 3.0);
  // Every kiln: key written is one of the above (a new key needs a line here).
  const std::vector<std::string> known = {"kiln:version", "kiln:scene", "kiln:camera", "kiln:spp", "kiln:spp_first",
                                          "kiln:spp_last", "kiln:spp_total", "kiln:scene_hash", "kiln:scene_files",
                                          "kiln:seed", "kiln:rules", "kiln:integrator", "kiln:render_options",
                                          "kiln:render_seconds", "kiln:filter", "kiln:mean_spp", "kiln:incomplete"};
  for (const auto& [key, value] : f.meta) {
    if (key.rfind("kiln:", 0) == 0) {
      EXPECT_NE(std::find(known.begin(), known.end(), key), known.end()) << key;
    }
  }
  // The crop: 200 x 200 pixels at (100, 50) in the 400 x 400 frame.
  EXPECT_EQ(f.rgb.width(), 200);
  EXPECT_EQ(f.rgb.height(), 200);
  EXPECT_EQ(f.window.x, 100);
  EXPECT_EQ(f.window.y, 50);
  EXPECT_EQ(f.window.full_width, 400);
  EXPECT_EQ(f.window.full_height, 400);
  ASSERT_EQ(f.aovs.size(), 1u);
  EXPECT_EQ(f.aovs[0].channels, std::vector<std::string>{"Z"});
}

// Why: the keys that only some runs write: the error against a reference (--reference) and the adaptive threshold.
TEST(ExrMetadata, ReferenceAndAdaptiveKeys) {
  const std::string dir = tmp_dir("exr_metadata_optional");
  const std::string small = default_scene() + " --spp 2 --seed 3";
  ASSERT_EQ(render(small + " -o " + dir + "/ref"), 0);
  ASSERT_EQ(render(small + " -o " + dir + "/run --reference " + dir + "/ref/default.exr"), 0);
  const ExrFile r = read_exr(dir + "/run/default.exr");
  EXPECT_EQ(r.find("kiln:reference"), dir + "/ref/default.exr");
  // Same seed and spp as the reference: the error is exactly zero.
  for (const char* key : {"kiln:mse", "kiln:relmse", "kiln:rmse"}) EXPECT_EQ(std::stod(r.find(key)), 0.0) << key;
  ASSERT_EQ(render(default_scene() + " --spp 8 --adaptive 0.05 -o " + dir + "/adaptive"), 0);
  EXPECT_DOUBLE_EQ(std::stod(read_exr(dir + "/adaptive/default.exr").find("kiln:adaptive_threshold")), 0.05);
}

}  // namespace
}  // namespace kiln::test
