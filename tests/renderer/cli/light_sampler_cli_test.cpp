// --light-sampler and --light-samplers through the command line: the sampler reaches the world (--stats, kiln info,
// the EXR's kiln:render_options), a bad name or a course scene is refused with exit 2, split renders with different
// samplers are not merged, and kiln converge measures each strategy with each sampler.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "renderer/image_io/image_io.h"
#include "renderer/render_util.h"

namespace kiln::test {
namespace {

namespace fs = std::filesystem;

const std::string kManyLights = std::string(KILN_SOURCE_DIR) + "/tests/data/pbrt/many_lights.pbrt";
const std::string kCoursePath = std::string(KILN_SOURCE_DIR) + "/scenes/killeroo_path.xml";

// Renders the many-lights scene's centre at 4 spp; returns its --stats JSON and EXR.
struct Rendered {
  RunResult run;
  nlohmann::json stats;
  ExrFile exr;
};
Rendered render_many_lights(const std::string& name, const std::string& args) {
  const std::string dir = tmp_dir("light_sampler_cli") + "/" + name;
  fs::remove_all(dir);
  Rendered r;
  r.run = run_kiln("render " + kManyLights + " -o " + dir + " -q --spp 4 --seed 3 --crop 16,48,16,48 --stats " + dir +
                   ".json " + args);
  if (r.run.exit_code != 0) return r;
  r.stats = nlohmann::json::parse(std::ifstream(dir + ".json"));
  r.exr = read_exr(dir + "/many_lights.exr");
  return r;
}

TEST(LightSamplerCli, TheSamplerReachesTheWorldStatsAndMetadata) {
  const Rendered bvh = render_many_lights("default", "");
  ASSERT_EQ(bvh.run.exit_code, 0) << bvh.run.output;
  const auto& ls = bvh.stats["world"]["built"]["light_sampler"];
  EXPECT_EQ(ls["kind"], "bvh");
  EXPECT_EQ(ls["emitters"], 96);
  EXPECT_GE(ls["nodes"].get<int>(), 32);  // 4-wide: at least (96 - 1) / 3
  EXPECT_LT(ls["nodes"].get<int>(), 96);
  EXPECT_GE(ls["build_seconds"].get<double>(), 0.0);
  EXPECT_NE(bvh.exr.find("kiln:render_options").find("light_sampler=bvh"), std::string::npos);

  const Rendered power = render_many_lights("power", "--light-sampler power");
  ASSERT_EQ(power.run.exit_code, 0) << power.run.output;
  EXPECT_EQ(power.stats["world"]["built"]["light_sampler"]["kind"], "power");
  EXPECT_FALSE(power.stats["world"]["built"]["light_sampler"].contains("nodes"));
  EXPECT_NE(power.exr.find("kiln:render_options").find("light_sampler=power"), std::string::npos);
  EXPECT_NE(power.exr.rgb.pixels()[100].r, bvh.exr.rgb.pixels()[100].r);
}

// Same seed, same image: the hierarchy is built in one thread and sampled without shared state.
TEST(LightSamplerCli, HierarchyRendersAreBitIdenticalForAnyThreadCount) {
  const Rendered one = render_many_lights("threads1", "--threads 1");
  const Rendered two = render_many_lights("threads2", "--threads 2 --reverse-tiles");
  ASSERT_EQ(one.run.exit_code, 0) << one.run.output;
  ASSERT_EQ(two.run.exit_code, 0) << two.run.output;
  ASSERT_EQ(one.exr.rgb.pixels().size(), two.exr.rgb.pixels().size());
  for (size_t i = 0; i < one.exr.rgb.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(one.exr.rgb.pixels()[i][c], two.exr.rgb.pixels()[i][c]) << "pixel " << i;
}

TEST(LightSamplerCli, InfoReportsTheSamplerAndItsTree) {
  const RunResult bvh = run_kiln("info " + kManyLights);
  ASSERT_EQ(bvh.exit_code, 0) << bvh.output;
  EXPECT_NE(bvh.output.find("light sampler: bvh (96 emitters, a 4-wide tree of "), std::string::npos) << bvh.output;
  const RunResult power = run_kiln("info " + kManyLights + " --light-sampler power");
  EXPECT_NE(power.output.find("light sampler: power\n"), std::string::npos) << power.output;
  // One light: the power selector, no tree.
  const RunResult one = run_kiln("info " + std::string(KILN_SOURCE_DIR) + "/scenes/default.xml");
  EXPECT_NE(one.output.find("light sampler: power\n"), std::string::npos) << one.output;
}

TEST(LightSamplerCli, BadNamesAndCourseScenesAreRefused) {
  const Rendered bad = render_many_lights("bad", "--light-sampler tree");
  EXPECT_EQ(bad.run.exit_code, 2) << bad.run.output;
  const RunResult course = run_kiln("render " + kCoursePath + " -o " + tmp_dir("light_sampler_cli") +
                                    "/course -q --spp 1 --crop 0,8,0,8 --light-sampler bvh");
  EXPECT_EQ(course.exit_code, 2) << course.output;
  EXPECT_NE(course.output.find("--light-sampler"), std::string::npos) << course.output;
  EXPECT_NE(course.output.find("course rules"), std::string::npos) << course.output;
  const RunResult kiln_rules = run_kiln("render " + kCoursePath + " -o " + tmp_dir("light_sampler_cli") +
                                        "/course_kiln -q --spp 1 --crop 0,8,0,8 --rules kiln --light-sampler bvh");
  EXPECT_EQ(kiln_rules.exit_code, 0) << kiln_rules.output;
  const RunResult converge = run_kiln("converge " + kManyLights + " --light-samplers power,tree -q -o " +
                                      tmp_dir("light_sampler_cli") + "/converge_bad");
  EXPECT_EQ(converge.exit_code, 2) << converge.output;
  EXPECT_NE(converge.output.find("unknown light sampler 'tree'"), std::string::npos) << converge.output;
}

TEST(LightSamplerCli, PartsRenderedWithDifferentSamplersAreNotMerged) {
  const std::string dir = tmp_dir("light_sampler_cli") + "/merge";
  fs::remove_all(dir);
  const std::string base = "render " + kManyLights + " -q --spp 4 --crop 16,48,16,48 ";
  ASSERT_EQ(run_kiln(base + "-o " + dir + "/a --spp-range 0:2").exit_code, 0);
  ASSERT_EQ(run_kiln(base + "-o " + dir + "/b --spp-range 2:4 --light-sampler power").exit_code, 0);
  const RunResult merged = run_kiln("merge " + dir + "/a/many_lights.exr " + dir + "/b/many_lights.exr -o " + dir +
                                    "/m.exr");
  EXPECT_EQ(merged.exit_code, 2) << merged.output;
  EXPECT_NE(merged.output.find("render options"), std::string::npos) << merged.output;
}

TEST(LightSamplerCli, ConvergeMeasuresEachStrategyWithEachSampler) {
  const std::string dir = tmp_dir("light_sampler_cli") + "/converge";
  fs::remove_all(dir);
  const RunResult r = run_kiln("converge " + kManyLights + " --strategies mis --light-samplers power,bvh --budget 2 "
                               "--runs 1 --reference-spp 16 --resolution-scale 0.25 --threads 2 -q -o " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("mis/power"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mis/bvh"), std::string::npos) << r.output;
  std::ifstream csv(dir + "/convergence.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\nmis/bvh,"), std::string::npos);
}

}  // namespace
}  // namespace kiln::test
