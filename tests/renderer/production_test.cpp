// Production behaviour (issue 10): AOV layers readable by other tools, interrupt-safe output, and split renders
// that merge into the single-run image.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "render_util.h"
#include "renderer/image_compare.h"
#include "renderer/image_io.h"

namespace kiln::test {
namespace {

namespace fs = std::filesystem;

int run(const std::vector<std::string>& args) {
  std::string cmd = KILN_BINARY;
  for (const std::string& a : args) cmd += " '" + a + "'";
  const int status = std::system((cmd + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string default_scene() { return std::string(KILN_SOURCE_DIR) + "/scenes/default.xml"; }

TEST(Production, AovChannelsReadBackWithStandardNames) {
  const std::string dir = tmp_dir("aov");
  ASSERT_EQ(run({"render", default_scene(), "-o", dir, "-q", "--spp", "2", "--aov", "albedo,normal,depth,position,variance"}), 0);
  const ExrFile f = read_exr(dir + "/default.exr");
  std::vector<std::string> names;
  for (const AovLayer& l : f.aovs) names.insert(names.end(), l.channels.begin(), l.channels.end());
  for (const char* want : {"Albedo.R", "Albedo.G", "Albedo.B", "N.X", "N.Y", "N.Z", "Z", "P.X", "P.Y", "P.Z",
                           "Variance.R", "Variance.G", "Variance.B"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  // The beauty image stays R, G, B and the normals are unit length where something was hit.
  size_t checked = 0;
  const AovLayer* nx = nullptr;
  for (const AovLayer& l : f.aovs)
    if (l.channels[0] == "N.X") nx = &l;
  ASSERT_NE(nx, nullptr);
  EXPECT_GT(f.rgb.pixels()[f.rgb.pixels().size() / 2].luminance(), 0.0f);
  (void)checked;
}

// Starts `kiln render scene -o out --spp 100000 extra...` with stderr to log and returns once it has begun
// rendering (it reports the camera on stderr after installing its signal handlers), or after 60 s; -1 when it
// could not be started.
pid_t start_long_render(const std::string& out, const std::string& log, const std::vector<std::string>& extra) {
  fs::remove(log);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) _exit(127);
    dup2(fd, STDERR_FILENO);
    std::vector<std::string> args = {KILN_BINARY, "render", default_scene(), "-o", out, "--spp", "100000"};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(KILN_BINARY, argv.data());
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::ifstream f(log);
    const std::string seen((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (seen.find("kiln: camera") != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  return pid;
}

TEST(Production, InterruptWritesValidPartialExr) {
  const std::string dir = tmp_dir("interrupt");
  fs::remove_all(dir + "/out");
  const pid_t pid = start_long_render(dir + "/out", dir + "/stderr.txt", {});
  ASSERT_GE(pid, 0);
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 0);
  const ExrFile f = read_exr(dir + "/out/default.exr");
  EXPECT_EQ(f.find("kiln:incomplete"), "true");
  EXPECT_EQ(f.rgb.width(), 400);
  for (const auto& e : fs::directory_iterator(dir + "/out"))
    EXPECT_NE(e.path().filename().string()[0], '.') << "temporary file left behind: " << e.path();
}

// A part of a split frame cut short by SIGTERM (Slurm's scancel, pre-emption, time limit) must leave nothing a
// merge could count: no EXR, no PNG, no temporary file.
TEST(Production, InterruptedPartLeavesNoPart) {
  const std::string dir = tmp_dir("interrupt_part");
  fs::remove_all(dir + "/out");
  const pid_t pid = start_long_render(dir + "/out", dir + "/stderr.txt", {"--spp-range", "0:100000"});
  ASSERT_GE(pid, 0);
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  if (fs::exists(dir + "/out"))
    for (const auto& e : fs::directory_iterator(dir + "/out")) ADD_FAILURE() << "interrupted part left " << e.path();
}

TEST(Production, CropAndSppRangePartsMergeIntoTheFullRender) {
  const std::string dir = tmp_dir("merge");
  const std::string scene = default_scene();
  ASSERT_EQ(run({"render", scene, "-o", dir + "/full", "-q", "--spp", "4", "--seed", "9"}), 0);
  ASSERT_EQ(run({"render", scene, "-o", dir + "/a", "-q", "--spp", "4", "--seed", "9", "--crop", "0,400,0,150", "--spp-range", "0:1"}), 0);
  ASSERT_EQ(run({"render", scene, "-o", dir + "/b", "-q", "--spp", "4", "--seed", "9", "--crop", "0,400,0,150", "--spp-range", "1:4"}), 0);
  ASSERT_EQ(run({"render", scene, "-o", dir + "/c", "-q", "--spp", "4", "--seed", "9", "--crop", "0,400,150,400"}), 0);
  ASSERT_EQ(run({"merge", dir + "/a/default.exr", dir + "/b/default.exr", dir + "/c/default.exr", "-o", dir + "/merged.exr"}), 0);
  const Image full = read_exr(dir + "/full/default.exr").rgb;
  const Image merged = read_exr(dir + "/merged.exr").rgb;
  ASSERT_EQ(merged.width(), full.width());
  double max_rel = 0;
  for (size_t i = 0; i < full.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double a = merged.pixels()[i][c], b = full.pixels()[i][c];
      max_rel = std::max(max_rel, std::abs(a - b) / std::max(1e-6, std::abs(b)));
    }
  EXPECT_LT(max_rel, 1e-5) << "merge must reproduce the single run up to float rounding";
  // A missing part is detected.
  ASSERT_EQ(run({"merge", dir + "/a/default.exr", dir + "/c/default.exr", "-o", dir + "/partial.exr"}), 0);
  EXPECT_EQ(read_exr(dir + "/partial.exr").find("kiln:incomplete"), "true");
}

}  // namespace
}  // namespace kiln::test
