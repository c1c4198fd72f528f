#include <tbb/global_control.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "core/error.h"
#include "renderer/cli/converge.h"
#include "renderer/analysis/convergence.h"
#include "renderer/image_io/image_io.h"
#include "renderer/integrators/rules.h"
#include "renderer/render/render.h"
#include "renderer/world/world.h"
#include "scenes/loader.h"

namespace kiln {
namespace {

std::atomic<bool> g_converge_interrupted{false};
extern "C" void on_converge_signal(int) { g_converge_interrupted.store(true); }

// The reference must not share random streams with any measured run (seed + 1 + r), or its errors would be
// correlated with theirs and relMSE would read low.
constexpr uint64_t kReferenceSeedTweak = 0x7265666572656e63ull;  // "referenc"

void write_text(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f || !(f << text) || !f.flush()) throw Error(path, "", "cannot write file");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw Error(path, "", "cannot move the finished file into place: " + ec.message());
}

// SIGINT / SIGTERM set the cancel flag while a study runs; the defaults come back however it ends.
struct SignalGuard {
  SignalGuard() {
    g_converge_interrupted.store(false);
    std::signal(SIGINT, on_converge_signal);
    std::signal(SIGTERM, on_converge_signal);
  }
  ~SignalGuard() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
  }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;
};

size_t delta_light_count(const SceneDesc& s) {
  return s.point_lights.size() + s.spot_lights.size() + s.directional_lights.size() + s.area_lights.size();
}

}  // namespace

int cmd_converge(const ConvergeArgs& args) {
  if (!(args.resolution_scale > 0.0) || !std::isfinite(args.resolution_scale))
    throw Error("--resolution-scale", "", "must be a positive number");
  if (!(args.budget_seconds > 0.0)) throw Error("--budget", "", "must be a positive number of seconds");
  if (args.runs < 1) throw Error("--runs", "", "must be at least 1");
  std::unique_ptr<tbb::global_control> threads;
  if (args.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(args.threads));

  SceneDesc scene = load_scene(args.scene);
  if (scene.cameras.empty()) throw Error(args.scene, "", "scene has no camera");
  auto cam_it = scene.cameras.begin();
  if (args.camera) {
    cam_it = std::find_if(scene.cameras.begin(), scene.cameras.end(), [&](const CameraDesc& c) { return c.id == *args.camera; });
    if (cam_it == scene.cameras.end()) throw Error(args.scene, "", "no camera with id '" + *args.camera + "'");
  }
  CameraDesc cd = *cam_it;
  cd.width = std::max(1, int(std::lround(cd.width * args.resolution_scale)));
  cd.height = std::max(1, int(std::lround(cd.height * args.resolution_scale)));

  // Validate every name before spending time on a reference.
  const std::vector<std::string> names = split_list(args.strategies);
  if (names.empty()) throw Error("--strategies", "", "no strategy given");
  const PathSettings base = convergence_base_settings(scene);
  bool all_nee = true;
  for (const std::string& n : names) all_nee &= kiln_strategy(n, base, "--strategies").nee;

  bool removed_delta = false;
  if (!all_nee && !args.keep_delta_lights && delta_light_count(scene) > 0) {
    if (!args.quiet)
      std::fprintf(stderr,
                   "kiln: converge: removing %zu point/spot/directional/area light(s): direction sampling never "
                   "reaches them, so strategies without NEE would converge to a different image "
                   "(--keep-delta-lights keeps them)\n",
                   delta_light_count(scene));
    scene.point_lights.clear();
    scene.spot_lights.clear();
    scene.directional_lights.clear();
    scene.area_lights.clear();
    removed_delta = true;
  }

  // Every strategy is one of Kiln's, so the world samples lights with Kiln's exact densities.
  WorldOptions wo;
  wo.accel = args.accel;
  const auto world = build_world(scene, wo);
  const Camera camera(cd);
  // A strategy of Kiln's path tracer, volumetric when the scene has media.
  const auto strategy = [&](const std::string& n) {
    NamedStrategy st = make_strategy(n, base, world->features);
    st.settings.method = kiln_path_integrator(std::get<PathSettings>(st.settings.method), scene, cd).method;
    return st;
  };
  std::vector<NamedStrategy> strategies;
  for (const std::string& n : names) strategies.push_back(strategy(n));

  const SignalGuard signals;
  std::filesystem::create_directories(args.out_dir);
  const std::filesystem::path dir(args.out_dir);

  Image reference;
  std::string reference_note;
  if (args.reference) {
    reference = read_exr(*args.reference).rgb;
    if (reference.width() != camera.width() || reference.height() != camera.height())
      throw Error(*args.reference, "",
                  "reference is " + std::to_string(reference.width()) + "x" + std::to_string(reference.height()) +
                      " but camera " + cd.id + " renders " + std::to_string(camera.width()) + "x" +
                      std::to_string(camera.height()) + " (check --resolution-scale)");
    reference_note = "reference " + std::filesystem::path(*args.reference).filename().string();
  } else {
    const NamedStrategy ref_strategy = strategy("mis");
    const std::string path = (dir / "reference.exr").string();
    if (!args.quiet)
      std::fprintf(stderr, "kiln: converge: no --reference given; rendering one with mis at %u spp (%dx%d) to %s\n",
                   args.reference_spp, camera.width(), camera.height(), path.c_str());
    RenderOptions ro;
    ro.seed = args.seed ^ kReferenceSeedTweak;
    ro.spp_total = args.reference_spp;
    ro.progress = !args.quiet;
    ro.cancel = &g_converge_interrupted;
    Film film(camera.width(), camera.height());
    const RenderStats rs = render_samples(*world, camera, ref_strategy.settings, ro, 0, args.reference_spp, film);
    reference = film.mean();
    write_exr(path, reference, {},
              {{"kiln:version", KILN_VERSION},
               {"kiln:scene", args.scene},
               {"kiln:camera", cd.id},
               {"kiln:spp", std::to_string(args.reference_spp)},
               {"kiln:integrator", ref_strategy.settings.describe()},
               {"kiln:render_seconds", std::to_string(rs.seconds)},
               {"kiln:incomplete", rs.cancelled ? "true" : "false"}});
    if (rs.cancelled) {
      std::fprintf(stderr, "kiln: converge: interrupted while rendering the reference\n");
      return 130;
    }
    if (!args.quiet) std::fprintf(stderr, "kiln: converge: reference took %.1fs\n", rs.seconds);
    reference_note = "reference mis " + std::to_string(args.reference_spp) + " spp";
  }

  ConvergenceOptions co;
  co.max_spp = args.max_spp;
  co.runs = args.runs;
  co.budget_seconds = args.budget_seconds / double(strategies.size());
  co.seed = args.seed;
  co.cancel = &g_converge_interrupted;
  std::vector<ConvergencePoint> points;
  std::vector<StrategySummary> summaries;
  for (const NamedStrategy& st : strategies) {
    if (g_converge_interrupted.load()) break;
    if (!args.quiet)
      std::fprintf(stderr, "kiln: converge: %-8s %s, %d run(s), %.1fs\n", st.name.c_str(), st.settings.describe().c_str(),
                   co.runs, co.budget_seconds);
    const std::vector<ConvergencePoint> p = measure_strategy(*world, camera, st, reference, co);
    if (p.empty()) continue;
    points.insert(points.end(), p.begin(), p.end());
    summaries.push_back(summarize(p));
  }

  const std::string stem = std::filesystem::path(args.scene).stem().string();
  char subtitle[512];
  std::snprintf(subtitle, sizeof subtitle, "camera %s, %dx%d, max depth %d, %s; %.0fs budget, %d run(s) per point%s",
                cd.id.c_str(), camera.width(), camera.height(), base.max_depth, reference_note.c_str(),
                args.budget_seconds, args.runs, removed_delta ? "; delta lights removed" : "");
  const std::string csv = (dir / "convergence.csv").string(), svg = (dir / "convergence.svg").string();
  write_text(csv, convergence_csv(points));
  write_text(svg, loglog_svg(convergence_plot(points, "Error against render time: " + stem, subtitle)));
  std::printf("%s", ranking_table(summaries).c_str());
  std::printf("%s\n%s\n", csv.c_str(), svg.c_str());
  std::fflush(stdout);

  if (g_converge_interrupted.load()) {
    std::fprintf(stderr, "kiln: converge: interrupted; wrote the points measured so far\n");
    return 130;
  }
  return 0;
}

}  // namespace kiln
