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

#include "renderer/render_util.h"
#include "renderer/analysis/image_compare.h"
#include "renderer/image_io/image_io.h"

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

// A camera at the origin looking down -z (FovY 90, square image) at a Lambertian plane z = -kPlaneDistance that
// fills the view, lit by a point light: every AOV value is known in closed form.
constexpr float kPlaneDistance = 2.0f;
constexpr int kAovRes = 16;
std::string aov_plane_scene() {
  return R"(<Scene rules="kiln">
  <MaxRecursionDepth>2</MaxRecursionDepth>
  <BackgroundColor>0 0 0</BackgroundColor>
  <Cameras><Camera id="1" type="lookAt"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
    <FovY>90</FovY><NearDistance>1</NearDistance><ImageResolution>16 16</ImageResolution>
    <ImageName>plane.exr</ImageName></Camera></Cameras>
  <Lights><PointLight id="1"><Position>0.3 0.2 -1</Position><Intensity>5 5 5</Intensity></PointLight></Lights>
  <Materials><Material id="1"><AmbientReflectance>0 0 0</AmbientReflectance>
    <DiffuseReflectance>0.1 0.2 0.3</DiffuseReflectance><SpecularReflectance>0 0 0</SpecularReflectance>
  </Material></Materials>
  <VertexData>-50 -50 -2 50 -50 -2 50 50 -2 -50 50 -2</VertexData>
  <Objects><Mesh id="1"><Material>1</Material><Faces>1 2 3 1 3 4</Faces></Mesh></Objects>
</Scene>
)";
}

const AovLayer& layer(const ExrFile& f, const std::string& channel) {
  for (const AovLayer& l : f.aovs)
    if (l.channels[0] == channel) return l;
  throw std::runtime_error("no channel " + channel);
}
float aov(const ExrFile& f, const std::string& channel, size_t pixel) { return layer(f, channel).data[pixel]; }

TEST(Production, AovChannelsReadBackWithStandardNames) {
  const std::string dir = tmp_dir("aov");
  ASSERT_EQ(run({"render", default_scene(), "-o", dir, "-q", "--spp", "2", "--aov", "albedo,normal,depth,position,variance"}), 0);
  const ExrFile f = read_exr(dir + "/default.exr");
  std::vector<std::string> names;
  for (const AovLayer& l : f.aovs) names.insert(names.end(), l.channels.begin(), l.channels.end());
  for (const char* want : {"Albedo.R", "Albedo.G", "Albedo.B", "N.X", "N.Y", "N.Z", "Z", "P.X", "P.Y", "P.Z",
                           "Variance.R", "Variance.G", "Variance.B"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  EXPECT_GT(f.rgb.pixels()[f.rgb.pixels().size() / 2].luminance(), 0.0f);
}

// Why: the values, not just the names. On the plane: albedo is the material's reflectance (the course's
// DiffuseReflectance kd is a radiance factor, L = kd E, i.e. a Lambertian reflectance of pi kd), normals are unit
// length and face the camera, position and depth are those of the pixel's central ray. The film averages the
// pixel's samples, which the sampler stratifies 2 x 2 at 4 spp, so the average point lies within half a stratum
// (a quarter pixel) of the centre's: a hard bound, far below a pixel (a half-pixel shift or a flipped axis fails).
TEST(Production, AovValuesMatchTheCameraGeometry) {
  const std::string dir = tmp_dir("aov_values");
  std::ofstream(dir + "/plane.xml") << aov_plane_scene();
  ASSERT_EQ(run({"render", dir + "/plane.xml", "-o", dir, "-q", "--spp", "4", "--aov", "all"}), 0);
  const ExrFile f = read_exr(dir + "/plane.exr");
  ASSERT_EQ(f.rgb.width(), kAovRes);
  constexpr float kPi = 3.14159265f;
  constexpr float kPixelOnPlane = 2.0f * kPlaneDistance / kAovRes;
  constexpr float kTol = kPixelOnPlane / 4.0f;  // half a stratum of the 2 x 2 grid
  for (int y = 0; y < kAovRes; ++y)
    for (int x = 0; x < kAovRes; ++x) {
      SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
      const size_t i = size_t(y) * kAovRes + size_t(x);
      EXPECT_NEAR(aov(f, "Albedo.R", i), 0.1f * kPi, 1e-6f);
      EXPECT_NEAR(aov(f, "Albedo.G", i), 0.2f * kPi, 1e-6f);
      EXPECT_NEAR(aov(f, "Albedo.B", i), 0.3f * kPi, 1e-6f);
      const Vec3f n{aov(f, "N.X", i), aov(f, "N.Y", i), aov(f, "N.Z", i)};
      EXPECT_NEAR(length(n), 1.0f, 1e-5f);
      EXPECT_GT(n.z, 0.999f) << "the normal must face the camera";
      // Central ray of pixel (x, y): image x to the right, image y downwards, near plane [-1, 1]^2 at distance 1.
      const float u = -1.0f + 2.0f * (float(x) + 0.5f) / kAovRes, v = 1.0f - 2.0f * (float(y) + 0.5f) / kAovRes;
      const Vec3f p = Vec3f{u, v, -1.0f} * kPlaneDistance;
      EXPECT_NEAR(aov(f, "P.X", i), p.x, kTol);
      EXPECT_NEAR(aov(f, "P.Y", i), p.y, kTol);
      EXPECT_NEAR(aov(f, "P.Z", i), p.z, kTol);
      // |grad depth| <= 1 per unit of P, plus the curvature of |P| over a pixel (< 0.01 here).
      EXPECT_NEAR(aov(f, "Z", i), length(p), kTol + 0.01f);
    }
}

// Why: the variance layer is the variance of the pixel's mean: never negative, and 4x the samples divide it by ~4
// (checked at < 1/2 over the mean of a 100 x 100 crop, far outside the noise of a mean over 10000 pixels).
TEST(Production, AovVarianceIsNonNegativeAndShrinksWithSamples) {
  const std::string dir = tmp_dir("aov_variance");
  double mean_variance[2] = {0, 0};
  const char* spp[2] = {"4", "16"};
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(run({"render", default_scene(), "-o", dir + "/" + spp[k], "-q", "--spp", spp[k], "--aov", "variance", "--crop", "150,250,150,250"}), 0);
    const ExrFile f = read_exr(dir + "/" + spp[k] + "/default.exr");
    for (const char* c : {"Variance.R", "Variance.G", "Variance.B"})
      for (float v : layer(f, c).data) {
        ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << c << " = " << v;
        mean_variance[k] += v;
      }
  }
  EXPECT_GT(mean_variance[0], 0.0);
  EXPECT_LT(mean_variance[1], 0.5 * mean_variance[0]) << "4 spp " << mean_variance[0] << ", 16 spp " << mean_variance[1];
  std::printf("variance of the mean, image sum: 4 spp %.4g, 16 spp %.4g (ratio %.3f, expected 0.25)\n",
              mean_variance[0], mean_variance[1], mean_variance[1] / mean_variance[0]);
}

// Why: the variance layer is the variance of the pixel mean's luminance, in the image's units: over 16 renders
// with different seeds, the pixels' means spread by as much as the layer says (the ratio of the two, averaged over a
// 40 x 40 crop, is 1 within the estimate's noise; the sample variance instead of the mean's would be 8 times too
// large at 8 spp, one divided by n once more 8 times too small).
TEST(Production, AovVarianceIsTheSpreadOfThePixelMeanAcrossSeeds) {
  const std::string dir = tmp_dir("aov_variance_seeds");
  constexpr int kSeeds = 16;
  std::vector<std::vector<double>> means;  // [pixel][seed], luminance
  double aov_sum = 0;
  size_t aov_count = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const std::string out = dir + "/seed" + std::to_string(seed);
    ASSERT_EQ(run({"render", default_scene(), "-o", out, "-q", "--spp", "8", "--seed", std::to_string(seed), "--aov",
                   "variance", "--crop", "150,190,150,190"}),
              0);
    const ExrFile f = read_exr(out + "/default.exr");
    means.resize(f.rgb.pixels().size());
    for (size_t i = 0; i < f.rgb.pixels().size(); ++i) means[i].push_back(f.rgb.pixels()[i].luminance());
    for (float v : layer(f, "Variance.R").data) {
      aov_sum += v;
      ++aov_count;
    }
  }
  double spread_sum = 0;
  for (const std::vector<double>& m : means) {
    double mean = 0, ss = 0;
    for (double v : m) mean += v / kSeeds;
    for (double v : m) ss += (v - mean) * (v - mean);
    spread_sum += ss / (kSeeds - 1);
  }
  const double aov_mean = aov_sum / double(aov_count), spread = spread_sum / double(means.size());
  std::printf("variance of the pixel mean: layer %.4g, across %d seeds %.4g (ratio %.3f)\n", aov_mean, kSeeds, spread,
              aov_mean / spread);
  EXPECT_GT(aov_mean / spread, 0.7);
  EXPECT_LT(aov_mean / spread, 1.4);
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

// SIGINT (Ctrl-C) and SIGTERM (kill, a batch system's time limit) on a full-frame render: exit 130, and the
// samples so far are kept as a complete, readable EXR marked kiln:incomplete, with no temporary file left.
TEST(Production, InterruptWritesValidPartialExr) {
  for (const int sig : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(sig == SIGINT ? "SIGINT" : "SIGTERM");
    const std::string dir = tmp_dir(sig == SIGINT ? "interrupt_int" : "interrupt_term");
    fs::remove_all(dir + "/out");
    const pid_t pid = start_long_render(dir + "/out", dir + "/stderr.txt", {});
    ASSERT_GE(pid, 0);
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    const ExrFile f = read_exr(dir + "/out/default.exr");
    EXPECT_EQ(f.find("kiln:incomplete"), "true");
    ASSERT_EQ(f.rgb.width(), 400);
    ASSERT_EQ(f.rgb.height(), 400);
    size_t lit = 0;
    for (const Rgb& p : f.rgb.pixels()) {
      ASSERT_TRUE(p.is_finite() && !p.has_negative());
      lit += p.luminance() > 0.0f;
    }
    EXPECT_GT(lit, 0u) << "the partial image must hold the samples rendered so far";
    const double mean_spp = std::stod(f.find("kiln:mean_spp"));
    EXPECT_GT(mean_spp, 0.0);
    EXPECT_LT(mean_spp, 100000.0);
    for (const auto& e : fs::directory_iterator(dir + "/out"))
      EXPECT_NE(e.path().filename().string()[0], '.') << "temporary file left behind: " << e.path();
  }
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
  ASSERT_EQ(run({"render", scene, "-o", dir + "/full", "-q", "--spp", "4", "--seed", "9", "--aov", "all"}), 0);
  ASSERT_EQ(run({"render", scene, "-o", dir + "/a", "-q", "--spp", "4", "--seed", "9", "--aov", "all", "--crop", "0,400,0,150", "--spp-range", "0:1"}), 0);
  ASSERT_EQ(run({"render", scene, "-o", dir + "/b", "-q", "--spp", "4", "--seed", "9", "--aov", "all", "--crop", "0,400,0,150", "--spp-range", "1:4"}), 0);
  ASSERT_EQ(run({"render", scene, "-o", dir + "/c", "-q", "--spp", "4", "--seed", "9", "--aov", "all", "--crop", "0,400,150,400"}), 0);
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
  // The AOVs come from the same samples as the colour (renderer/integrators/aov.h), so the parts' layers merge into
  // the single run's too. Variance is left out: the merged one is that of the merged mean, from each part's spread.
  const ExrFile full_exr = read_exr(dir + "/full/default.exr"), merged_exr = read_exr(dir + "/merged.exr");
  ASSERT_EQ(merged_exr.aovs.size(), full_exr.aovs.size());
  for (size_t k = 0; k < full_exr.aovs.size(); ++k) {
    const AovLayer &a = merged_exr.aovs[k], &b = full_exr.aovs[k];
    ASSERT_EQ(a.channels, b.channels);
    if (a.channels[0].rfind("Variance.", 0) == 0) continue;
    double max_err = 0;
    for (size_t i = 0; i < b.data.size(); ++i)
      max_err = std::max(max_err, std::abs(double(a.data[i]) - b.data[i]) / std::max(1.0, std::abs(double(b.data[i]))));
    EXPECT_LT(max_err, 1e-5) << a.channels[0] << ": merge must reproduce the single run's AOV";
  }
  // A missing part is detected.
  ASSERT_EQ(run({"merge", dir + "/a/default.exr", dir + "/c/default.exr", "-o", dir + "/partial.exr"}), 0);
  EXPECT_EQ(read_exr(dir + "/partial.exr").find("kiln:incomplete"), "true");
}

}  // namespace
}  // namespace kiln::test
