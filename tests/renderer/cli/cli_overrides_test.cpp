// Through the command line: which integrator each scene gets, every rule override reaching the render (named in
// the EXR's kiln:integrator and changing the pixels), and bit-identical output for repeated runs, 1, 2 and 3
// threads and the in-house BVH.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"
#include "support/shared_data.h"

namespace kiln::test {
namespace {

namespace fs = std::filesystem;

std::string bundled(const std::string& rel) { return std::string(KILN_SOURCE_DIR) + "/scenes/" + rel; }

// A 64 x 64 crop of the default scene's centre (glass and gold spheres, walls, the light's reflection): cheap, and
// every transport path of the full frame is in it.
constexpr const char* kCrop = "168,232,168,232";

struct RenderRun {
  int exit_code = -1;
  ExrFile exr;
};

// kiln render <scene> -o <dir>/<name> -q <args>; reads the EXR named `image` when the run succeeded.
RenderRun render(const std::string& scene, const std::string& name, const std::string& args,
           const std::string& image = "default.exr") {
  const std::string dir = tmp_dir("cli_overrides") + "/" + name;
  fs::remove_all(dir);
  const std::string cmd = std::string(KILN_BINARY) + " render " + scene + " -o " + dir + " -q " + args + " > " +
                          dir + ".log 2>&1";
  const int status = std::system(cmd.c_str());
  RenderRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (r.exit_code == 0) r.exr = read_exr(dir + "/" + image);
  return r;
}

bool same_pixels(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height()) return false;
  for (size_t i = 0; i < a.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (a.pixels()[i][c] != b.pixels()[i][c]) return false;
  return true;
}

// Why: the scene's file decides the rules and the rules the integrator; nothing else (no format strings).
TEST(CliOverrides, EachSceneGetsItsRulesIntegrator) {
  const RenderRun kiln = render(bundled("default.xml"), "sel_kiln", std::string("--spp 1 --crop ") + kCrop);
  ASSERT_EQ(kiln.exit_code, 0);
  EXPECT_EQ(kiln.exr.find("kiln:rules"), "Kiln's rules");
  EXPECT_EQ(kiln.exr.find("kiln:integrator"), "Kiln path tracer: brdf+nee+mis+rr, max depth 8");
  const RenderRun rays = render(bundled("killeroo_blinnphong.xml"), "sel_rays", "--spp 1 --camera 1 --crop 0,32,0,32", "killeroo_blinnphong.exr");
  ASSERT_EQ(rays.exit_code, 0);
  EXPECT_EQ(rays.exr.find("kiln:rules"), "CENG795 course rules");
  EXPECT_EQ(rays.exr.find("kiln:integrator").rfind("course ray tracer", 0), 0u) << rays.exr.find("kiln:integrator");
  const RenderRun path = render(bundled("killeroo_path.xml"), "sel_path", "--spp 1 --crop 0,32,0,32", "killeroo_path.exr");
  ASSERT_EQ(path.exit_code, 0);
  EXPECT_EQ(path.exr.find("kiln:integrator"), "course path tracer: brdf+nee+fresnel-split, max depth 6");
  const RenderRun cs171 = render(bundled("cs171/configs/simple.json"), "sel_cs171", "--spp 1 --crop 0,32,0,32", "simple.exr");
  ASSERT_EQ(cs171.exit_code, 0);
  EXPECT_EQ(cs171.exr.find("kiln:rules"), "CS171 course rules");
  EXPECT_EQ(cs171.exr.find("kiln:integrator"), "Kiln path tracer: brdf+nee, max depth 12");
}

// Why: every override reaches the integrator (named in the metadata) and changes the image; --rules kiln on a
// course scene swaps the course's integrator for Kiln's.
TEST(CliOverrides, EveryRuleOverrideReachesTheRender) {
  const std::string base = std::string("--spp 4 --seed 5 --crop ") + kCrop;
  const RenderRun ref = render(bundled("default.xml"), "base", base);
  ASSERT_EQ(ref.exit_code, 0);
  struct Case {
    const char* name;
    const char* args;
    const char* integrator;
  };
  const Case cases[] = {
      {"strategy", "--strategy cosine", "Kiln path tracer: cosine+rr, max depth 8"},
      {"rr", "--rr false", "Kiln path tracer: brdf+nee+mis, max depth 8"},
      {"max_depth", "--max-depth 2", "Kiln path tracer: brdf+nee+mis+rr, max depth 2"},
      {"clamp", "--clamp 0.5", "Kiln path tracer: brdf+nee+mis+rr, max depth 8, clamp 0.500000"},
  };
  for (const Case& c : cases) {
    const RenderRun r = render(bundled("default.xml"), c.name, base + " " + c.args);
    ASSERT_EQ(r.exit_code, 0) << c.args;
    EXPECT_EQ(r.exr.find("kiln:integrator"), c.integrator) << c.args;
    EXPECT_FALSE(same_pixels(r.exr.rgb, ref.exr.rgb)) << c.args << " left the image unchanged";
  }
  // Under the course's rules: --rr true turns on the course roulette (literal coin flips), --course-roulette
  // expected its expected-value form; --rules kiln gives Kiln's path tracer.
  const std::string course = "--spp 1 --seed 5 --crop 0,32,0,32";
  const struct {
    const char* name;
    const char* args;
    const char* integrator;
  } course_cases[] = {
      {"course_rr", "--rr true", "course path tracer: brdf+nee+course-rr(literal)+fresnel-split, max depth unlimited"},
      {"course_expected", "--rr true --course-roulette expected",
       "course path tracer: brdf+nee+course-rr(expected)+fresnel-split, max depth unlimited"},
      {"rules_kiln", "--rules kiln", "Kiln path tracer: brdf+nee+mis+rr, max depth 6"},
  };
  for (const auto& c : course_cases) {
    const RenderRun r = render(bundled("killeroo_path.xml"), c.name, course + " " + c.args, "killeroo_path.exr");
    ASSERT_EQ(r.exit_code, 0) << c.args;
    EXPECT_EQ(r.exr.find("kiln:integrator"), c.integrator) << c.args;
  }
}

// Why: --time-limit stops the doubling waves before the budget (so far fewer samples than --spp), --reference
// writes one CSV line per wave with its error against the reference.
TEST(CliOverrides, TimeLimitAndReference) {
  const RenderRun limited = render(bundled("default.xml"), "time_limit", std::string("--spp 1000000 --time-limit 1"));
  ASSERT_EQ(limited.exit_code, 0);
  const int spp = std::stoi(limited.exr.find("kiln:spp"));
  EXPECT_GE(spp, 1);
  EXPECT_LT(spp, 1000000);
  EXPECT_EQ(limited.exr.find("kiln:incomplete"), "false");
  const RenderRun ref = render(bundled("default.xml"), "reference_ref", "--spp 8 --seed 1");
  ASSERT_EQ(ref.exit_code, 0);
  const std::string ref_path = tmp_dir("cli_overrides") + "/reference_ref/default.exr";
  const RenderRun run = render(bundled("default.xml"), "reference_run", "--spp 4 --seed 2 --reference " + ref_path);
  ASSERT_EQ(run.exit_code, 0);
  std::ifstream csv(tmp_dir("cli_overrides") + "/reference_run/default.convergence.csv");
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(csv, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u) << "header + waves of 1, 2, 4 spp";
  EXPECT_EQ(lines[0], "spp,seconds,mse,relmse,rmse");
  double previous = INFINITY;
  for (size_t i = 1; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].substr(0, lines[i].find(',')), std::to_string(1 << (i - 1)));
    const double mse = std::stod(lines[i].substr(lines[i].find(',', lines[i].find(',') + 1) + 1));
    EXPECT_GT(mse, 0.0);
    EXPECT_LT(mse, previous) << "the error falls with spp";
    previous = mse;
  }
}

// Why: --physical-lights replaces the course's object-space ellipsoid density (biased under non-uniform scale) by
// the exact one: the image of the course's ellipsoid light scene must change by far more than its noise.
TEST(CliOverrides, PhysicalLightsChangesTheEllipsoidImage) {
  const std::string scene = shared_dir() + "/scenes/ceng795/directLighting/cornellbox_jaroslav_glossy_area_ellipsoid.xml";
  KILN_NEED_SHARED_PATH(scene);
  const std::string args = "--spp 16 --crop 128,384,256,512 --aov variance";
  const std::string image = "cornellbox_jaroslav_glossy_area_ellipsoid.exr";
  const RenderRun course = render(scene, "course_ellipsoid", args, image);
  const RenderRun physical = render(scene, "physical_ellipsoid", args + " --physical-lights", image);
  ASSERT_EQ(course.exit_code, 0);
  ASSERT_EQ(physical.exit_code, 0);
  // Image mean and its standard error from the per-pixel variance of the mean (the AOV).
  const auto mean_and_se = [](const ExrFile& f) {
    double sum = 0, var = 0;
    for (const Rgb& p : f.rgb.pixels()) sum += p.luminance();
    for (const AovLayer& l : f.aovs)
      if (l.channels[0] == "Variance.R")
        for (float v : l.data) var += v;  // luminance variance, stored as grey
    const double n = double(f.rgb.pixels().size());
    return std::pair{sum / n, std::sqrt(var) / n};
  };
  const auto [m0, s0] = mean_and_se(course.exr);
  const auto [m1, s1] = mean_and_se(physical.exr);
  const double z = std::abs(m1 - m0) / std::hypot(s0, s1);
  std::printf("ellipsoid light: course density %.5f +- %.5f, exact %.5f +- %.5f, |z| = %.1f\n", m0, s0, m1, s1, z);
  EXPECT_GT(z, 6.0);
}

// Why: the same seed gives a bit-identical EXR for Kiln's default (MIS + roulette: roulette draws must not depend
// on scheduling), for 1, 2 and 3 threads, and for the in-house BVH.
TEST(CliOverrides, DeterministicAcrossRunsThreadsAndAccelerators) {
  const std::string base = std::string("--spp 4 --seed 11 --crop ") + kCrop;
  const RenderRun one = render(bundled("default.xml"), "det_t1", base + " --threads 1");
  ASSERT_EQ(one.exit_code, 0);
  EXPECT_EQ(one.exr.find("kiln:integrator"), "Kiln path tracer: brdf+nee+mis+rr, max depth 8");
  for (const char* extra : {"--threads 1", "--threads 2", "--threads 3", "--threads 3 --reverse-tiles"}) {
    const RenderRun r = render(bundled("default.xml"), "det_again", base + " " + extra);
    ASSERT_EQ(r.exit_code, 0);
    EXPECT_TRUE(same_pixels(r.exr.rgb, one.exr.rgb)) << extra;
  }
  const RenderRun bvh1 = render(bundled("default.xml"), "det_bvh1", base + " --accel bvh --threads 1");
  const RenderRun bvh3 = render(bundled("default.xml"), "det_bvh3", base + " --accel bvh --threads 3 --reverse-tiles");
  ASSERT_EQ(bvh1.exit_code, 0);
  ASSERT_EQ(bvh3.exit_code, 0);
  EXPECT_TRUE(same_pixels(bvh1.exr.rgb, bvh3.exr.rgb));
}

}  // namespace
}  // namespace kiln::test
