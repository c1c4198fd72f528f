#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "core/error.h"
#include "renderer/cli/converge.h"
#include "renderer/cli/interrupt.h"
#include "renderer/analysis/convergence.h"
#include "renderer/analysis/convergence_budget.h"
#include "renderer/image_io/image_io.h"
#include "renderer/integrators/rules.h"
#include "renderer/render/progressive.h"
#include "renderer/render/render.h"
#include "renderer/world/world.h"
#include "scenes/loader.h"

namespace kiln {
namespace {

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

struct RenderedReference {
  Image image;
  uint32_t spp = 0;
  double seconds = 0.0, seconds_per_spp = 0.0;
  bool cancelled = false;
};

struct SamplerWorld {
  std::string label;  // the sampler's name when --light-samplers was given, else empty
  std::unique_ptr<World> world;
};

struct MeasuredStrategy {
  NamedStrategy strategy;
  const World* world;
};

// The scene's world for each light sampler of --light-samplers, or its default world.
std::vector<SamplerWorld> build_sampler_worlds(const SceneDesc& scene, const ConvergeArgs& args) {
  WorldOptions wo;
  wo.accel = args.accel;
  std::vector<SamplerWorld> worlds;
  const std::vector<std::string> samplers = split_list(args.light_samplers);
  for (const std::string& name : samplers)
    if (!parse_light_sampler(name))
      throw Error("--light-samplers", "", "unknown light sampler '" + name + "' (power, uniform, bvh)");
  for (const std::string& name : samplers) {
    wo.light_sampler = parse_light_sampler(name);
    worlds.push_back({name, build_world(scene, wo)});
  }
  if (worlds.empty()) worlds.push_back({"", build_world(scene, wo)});
  return worlds;
}

// The pilot's doubling waves (renderer/render/progressive.h): its spp, time, and the last wave's cost per sample.
struct Pilot {
  uint32_t spp = 0;
  double seconds = 0.0, seconds_per_spp = 0.0;
  bool cancelled = false;
};

Pilot run_pilot(const World& world, const Camera& camera, const NamedStrategy& strategy, const RenderOptions& ro,
                uint32_t max_spp, double time_limit, Film& film) {
  ProgressiveOptions po;
  po.time_limit_seconds = time_limit;
  const ProgressiveResult pr = render_progressive(world, camera, strategy.settings, ro, max_spp, po, film);
  Pilot p;
  p.spp = pr.spp;
  p.seconds = pr.stats.seconds;
  p.cancelled = pr.stats.cancelled;
  if (!pr.waves.empty()) {
    const WaveReport& last = pr.waves.back();
    const WaveRange range = wave_range(last.wave, max_spp);
    p.seconds_per_spp = last.wave_seconds / double(std::max(1u, range.last - range.first));
  }
  return p;
}

// The reference when none is given (renderer/analysis/convergence_budget.h): a pilot measures the cost per sample,
// the plan is announced, and the same film continues to the planned spp. Written to `path`.
RenderedReference render_reference(const World& world, const Camera& camera, const std::string& camera_id,
                                   const NamedStrategy& strategy, const ConvergeArgs& args, const std::string& path,
                                   const std::atomic<bool>& cancel) {
  const double share = kReferenceShare * args.budget_seconds;
  const uint32_t requested = args.reference_spp.value_or(0);
  const uint32_t max_spp = requested > 0 ? requested : kDefaultReferenceMaxSpp;
  RenderOptions ro;
  ro.seed = args.seed ^ kReferenceSeedTweak;
  ro.spp_total = kProgressiveSppTotal;  // as the pilot's waves render them, so the continuation matches
  ro.cancel = &cancel;
  Film film(camera.width(), camera.height());
  const Pilot pilot = run_pilot(world, camera, strategy, ro, max_spp, kPilotShare * share, film);
  const ReferencePlan plan = plan_reference(share, pilot.spp, pilot.seconds, pilot.seconds_per_spp, max_spp, requested);
  if (!args.quiet) {
    const std::string why = requested > 0 ? "as --reference-spp asks"
                                          : "at most " + std::to_string(kDefaultReferenceMaxSpp) + " spp within " +
                                                std::to_string(int(std::lround(100 * kReferenceShare))) +
                                                "% of the --budget";
    std::fprintf(stderr,
                 "kiln: converge: no --reference given; rendering one with mis at %u spp (%dx%d) to %s: about %.1fs "
                 "(%.3gs per spp, measured on %u spp), %s\n",
                 plan.spp, camera.width(), camera.height(), path.c_str(), plan.estimated_seconds, pilot.seconds_per_spp,
                 pilot.spp, why.c_str());
    if (!plan.fits)
      std::fprintf(stderr,
                   "kiln: converge: warning: the reference alone will take about %.0fs, more than %.0f%% of the %.0fs "
                   "budget; the study will take about %.0fs in all (leave --reference-spp out to fit the budget)\n",
                   plan.estimated_seconds, 100 * kReferenceShare, args.budget_seconds,
                   plan.estimated_seconds + strategies_budget(args.budget_seconds, plan.estimated_seconds));
  }
  RenderedReference r;
  r.spp = plan.spp;
  r.seconds = pilot.seconds;
  r.seconds_per_spp = pilot.seconds_per_spp;
  r.cancelled = pilot.cancelled;
  if (!r.cancelled && plan.spp > pilot.spp) {
    ro.progress = !args.quiet;
    const RenderStats rs = render_samples(world, camera, strategy.settings, ro, pilot.spp, plan.spp, film);
    r.seconds += rs.seconds;
    r.cancelled = rs.cancelled;
  }
  r.image = film.mean();
  write_exr(path, r.image, {},
            {{"kiln:version", KILN_VERSION},
             {"kiln:scene", args.scene},
             {"kiln:camera", camera_id},
             {"kiln:spp", std::to_string(plan.spp)},
             {"kiln:integrator", strategy.settings.describe()},
             {"kiln:render_seconds", std::to_string(r.seconds)},
             {"kiln:incomplete", r.cancelled ? "true" : "false"}});
  if (!args.quiet && !r.cancelled) std::fprintf(stderr, "kiln: converge: reference took %.1fs\n", r.seconds);
  return r;
}

// Every run renders at least 1 spp, whatever its part of the budget: when that minimum (at about the reference's cost
// per spp) exceeds the strategies' part, the study will overrun, and the user hears so before it starts.
void warn_if_one_spp_overruns(const ConvergeArgs& args, size_t strategies, double seconds_per_spp,
                              double reference_seconds) {
  const double minimum = double(strategies) * double(args.runs) * seconds_per_spp;
  const double part = strategies_budget(args.budget_seconds, reference_seconds);
  if (args.quiet || minimum <= part) return;
  std::fprintf(stderr,
               "kiln: converge: warning: %zu strategies x %d run(s) need at least 1 spp each, about %.0fs at %.3gs per "
               "spp, more than the %.0fs left of the budget: the study will take about %.0fs (lower --runs, "
               "--strategies or --resolution-scale, or raise --budget)\n",
               strategies, args.runs, minimum, seconds_per_spp, part, reference_seconds + minimum);
}

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

  // Every strategy is one of Kiln's, so the world samples lights with Kiln's exact densities; one world per light
  // sampler (the light sampler is part of the immutable world).
  const std::vector<SamplerWorld> worlds = build_sampler_worlds(scene, args);
  const World& first_world = *worlds.front().world;
  const Camera camera(cd);
  // A strategy of Kiln's path tracer for one world, volumetric when the scene has media.
  const auto strategy = [&](const std::string& n, const World& w) {
    NamedStrategy st = make_strategy(n, base, w.features);
    st.settings.method = kiln_path_integrator(std::get<PathSettings>(st.settings.method), scene, cd).method;
    return st;
  };
  std::vector<MeasuredStrategy> strategies;
  for (const SamplerWorld& sw : worlds)
    for (const std::string& n : names) {
      NamedStrategy st = strategy(n, *sw.world);
      if (!sw.label.empty()) st.name += "/" + sw.label;
      strategies.push_back({std::move(st), sw.world.get()});
    }

  const InterruptGuard interrupt;
  std::filesystem::create_directories(args.out_dir);
  const std::filesystem::path dir(args.out_dir);

  Image reference;
  std::string reference_note;
  double reference_seconds = 0.0;
  if (args.reference) {
    reference = read_exr(*args.reference).rgb;
    if (reference.width() != camera.width() || reference.height() != camera.height())
      throw Error(*args.reference, "",
                  "reference is " + std::to_string(reference.width()) + "x" + std::to_string(reference.height()) +
                      " but camera " + cd.id + " renders " + std::to_string(camera.width()) + "x" +
                      std::to_string(camera.height()) + " (check --resolution-scale)");
    reference_note = "reference " + std::filesystem::path(*args.reference).filename().string();
  } else {
    const RenderedReference r =
        render_reference(first_world, camera, cd.id, strategy("mis", first_world), args,
                         (dir / "reference.exr").string(), interrupt.flag());
    if (r.cancelled) {
      std::fprintf(stderr, "kiln: converge: interrupted while rendering the reference\n");
      return 130;
    }
    reference = r.image;
    reference_seconds = r.seconds;
    reference_note = "reference mis " + std::to_string(r.spp) + " spp";
    warn_if_one_spp_overruns(args, strategies.size(), r.seconds_per_spp, r.seconds);
  }

  ConvergenceOptions co;
  co.max_spp = args.max_spp;
  co.runs = args.runs;
  co.budget_seconds = strategies_budget(args.budget_seconds, reference_seconds) / double(strategies.size());
  co.seed = args.seed;
  co.cancel = &interrupt.flag();
  std::vector<ConvergencePoint> points;
  std::vector<StrategySummary> summaries;
  for (const MeasuredStrategy& ms : strategies) {
    if (interrupt.interrupted()) break;
    const NamedStrategy& st = ms.strategy;
    if (!args.quiet)
      std::fprintf(stderr, "kiln: converge: %-8s %s, %d run(s), %.1fs\n", st.name.c_str(), st.settings.describe().c_str(),
                   co.runs, co.budget_seconds);
    const std::vector<ConvergencePoint> p = measure_strategy(*ms.world, camera, st, reference, co);
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

  if (interrupt.interrupted()) {
    std::fprintf(stderr, "kiln: converge: interrupted; wrote the points measured so far\n");
    return 130;
  }
  return 0;
}

}  // namespace kiln
