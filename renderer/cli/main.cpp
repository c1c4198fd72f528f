// kiln: command-line entry point. Every option has a help string; bad input exits with code 2.
#include <CLI/CLI.hpp>

#include "core/error.h"
#include "core/process_exit.h"
#include "renderer/cli/commands.h"
#include "renderer/cli/converge.h"
#include "renderer/cli/profile.h"

namespace {
constexpr const char* kLightSamplerHelp =
    "How next event estimation chooses lights (Kiln's rules): bvh (the light hierarchy: by importance at the shading "
    "point, mesh lights triangle by triangle), power (in proportion to power) or uniform. Default: bvh when the scene "
    "has several lights with a position or a large emissive mesh, else power";
}  // namespace

int main(int argc, char** argv) {
  using namespace kiln;
  const ExitCleanlyOnReturn exit_cleanly;
  CLI::App app{"Kiln: an Embree-accelerated CPU path tracer for CENG795 XML, CS171 JSON, pbrt-v4 and PLY/OBJ scenes"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("kiln ") + KILN_VERSION);

  RenderArgs ra;
  std::string accel = "embree";
  auto* render = app.add_subcommand("render", "Render every camera of a scene (or one) to linear EXR + PNG preview");
  render->add_option("scene", ra.scene, "Scene file: .xml (CENG795), .json (CS171), .pbrt (pbrt-v4), .ply or .obj (quick look)")->required();
  render->add_option("-o,--output", ra.out_dir, "Output folder (created if missing)")->capture_default_str();
  render->add_option("--camera", ra.camera, "Render only the camera with this id");
  render->add_option("--spp", ra.spp, "Samples per pixel (default: the camera's NumSamples)")->check(CLI::PositiveNumber);
  render->add_option("--threads", ra.threads, "Worker threads (0: all cores); output does not depend on it")->capture_default_str();
  render->add_option("--seed", ra.seed, "Random seed; the same seed gives a bit-identical image")->capture_default_str();
  render->add_option("--stats", ra.stats_path, "Write machine-readable statistics (JSON) to this file");
  render->add_flag("-q,--quiet", ra.quiet, "No progress bar or summary on stderr");
  render->add_option("--accel", accel, "Ray-query backend: embree or bvh (the in-house SAH BVH)")
      ->check(CLI::IsMember({"embree", "bvh"}))->capture_default_str();
  render->add_option("--rules", ra.rules.rules,
                     "Whose rules render the scene: kiln (MIS, unbiased roulette, exact pdfs) or course (the course "
                     "reference renderer's conventions; CENG795 and CS171 scenes). Default: the scene's own")
      ->check(CLI::IsMember({"kiln", "course"}));
  render->add_option("--strategy", ra.rules.strategy,
                     "Render with Kiln's path tracer and this strategy: uniform, cosine, brdf (no NEE), nee, mis (NEE + "
                     "BRDF, power heuristic); +rr turns roulette on (e.g. nee+rr); in media, +hero weights by the "
                     "tracked channel alone (no MIS over the RGB channels)");
  render->add_option("--rr", ra.rules.russian_roulette, "Russian roulette on/off (true/false)");
  render->add_option("--light-sampler", ra.rules.light_sampler, kLightSamplerHelp)
      ->check(CLI::IsMember({"power", "uniform", "bvh"}));
  render->add_option("--course-roulette", ra.rules.course_roulette,
                     "How CENG795 RussianRoulette cameras are rendered: literal (default: the course's own coin flips, "
                     "so a render at the scene's spp looks like the course's; unbounded variance) or expected (the "
                     "same expected image with finite variance: the course's weights, ended by Kiln's unbiased "
                     "roulette)")
      ->check(CLI::IsMember({"expected", "literal"}));
  render->add_option("--max-depth", ra.rules.max_depth, "Maximum bounces after the camera ray (-1: unlimited, needs --rr)");
  render->add_option("--clamp", ra.rules.clamp, "Clamp per-sample radiance to this maximum (biased; 0 = off)")->capture_default_str();
  render->add_option("--subdivide", ra.subdivide, "Loop-subdivide every mesh this many times");
  render->add_option("--crop", ra.crop, "Render only pixels x0,x1,y0,y1 (x1, y1 exclusive); written as an EXR data window");
  render->add_option("--spp-range", ra.spp_range,
                     "Render only sample indices FIRST:LAST (LAST exclusive) of the frame; seeds follow the absolute "
                     "index, so parts from `kiln merge` equal a single run");
  render->add_option("--filter", ra.filter,
                     "Pixel filter NAME[:WIDTH], WIDTH the full width in pixels: box (default width 1), triangle (2), "
                     "gaussian (3), blackman-harris (1.5, Cycles' default) or mitchell (4); default: the scene's "
                     "filter, else box:1. gaussian:0.01 samples pixel centres");
  render->add_option("--adaptive", ra.adaptive,
                     "Adaptive sampling: stop each pixel once its noise estimate is below this threshold (Cycles' "
                     "Noise Threshold, e.g. 0.01); --spp is then the maximum")
      ->check(CLI::PositiveNumber);
  render->add_option("--adaptive-min-spp", ra.adaptive_min_spp,
                     "Samples every pixel takes before adaptive sampling may stop it (0: Cycles' automatic "
                     "max(4, ceil(16 / threshold^0.3)), 64 at 0.01)")
      ->capture_default_str();
  render->add_option("--aov", ra.aovs, "Extra EXR layers: albedo,normal,depth,position,variance (or all)");
  render->add_option("--time-limit", ra.time_limit,
                     "Render in waves of doubling spp until the next wave would exceed this many seconds (--spp caps it)");
  render->add_option("--reference", ra.reference,
                     "Reference EXR: after every doubling of spp write spp,seconds,mse,relmse,rmse to "
                     "<image>.convergence.csv; final figures go into the EXR metadata and --stats");
  render->add_flag("--physical-lights", ra.rules.physical_lights,
                   "Under the course's rules, sample ellipsoid lights with their exact density (README)");
  render->add_flag("--all-features", ra.all_features, "Render with every feature code path enabled (to measure the mask's gain)")
      ->group("");
  render->add_flag("--reverse-tiles", ra.reverse_tiles, "Schedule tiles in reverse order (determinism checks)")->group("");

  InfoArgs ia;
  auto* info = app.add_subcommand("info", "List what a scene contains, what of it is rendered, substituted or "
                                          "ignored (per pbrt directive), and which renderer parts it needs");
  info->add_option("scene", ia.scene, "Scene file")->required();
  info->add_option("--subdivide", ia.subdivide, "Loop-subdivide every mesh this many times");
  info->add_option("--rules", ia.overrides.rules, "Show the integrators under these rules: kiln or course")
      ->check(CLI::IsMember({"kiln", "course"}));
  info->add_option("--light-sampler", ia.overrides.light_sampler, kLightSamplerHelp)
      ->check(CLI::IsMember({"power", "uniform", "bvh"}));
  info->add_flag("--json", ia.json, "Print one JSON object (every directive's outcome, features, counts)");
  info->add_flag("--allow-missing", ia.allow_missing,
                 "pbrt: report missing PLY meshes and included files and leave them out instead of failing "
                 "(to survey a scene collection without its large files)");

  std::string cmp_image, cmp_ref;
  int cmp_block = 32;
  auto* compare = app.add_subcommand("compare", "Compare an EXR with a reference EXR (block luminance, MSE, relMSE)");
  compare->add_option("image", cmp_image, "Rendered EXR")->required();
  compare->add_option("reference", cmp_ref, "Reference EXR")->required();
  compare->add_option("--block", cmp_block, "Block size in pixels for the block statistics")->capture_default_str();

  ConvergeArgs ca;
  std::string ca_accel = "embree";
  auto* converge = app.add_subcommand("converge", "Error against render time for several strategies: CSV, SVG plot and an efficiency ranking");
  converge->add_option("scene", ca.scene, "Scene file")->required();
  converge->add_option("--camera", ca.camera, "Camera id (default: the scene's first camera)");
  converge->add_option("--reference", ca.reference, "Reference EXR at the rendered resolution (default: render one with mis)");
  converge->add_option("--strategies", ca.strategies, "Comma-separated: uniform, cosine, brdf, nee, mis, each optionally +rr (and, in media, +hero)")->capture_default_str();
  converge->add_option("--light-samplers", ca.light_samplers, "Comma-separated light samplers (power, uniform, bvh): "
                       "every strategy is measured with each, named STRATEGY/SAMPLER (default: the scene's own only)");
  converge->add_option("--budget", ca.budget_seconds,
                       "The study's total render seconds. Without --reference, a reference is rendered first within "
                       "half of it (as many spp as fit, at most 4096; its spp and estimated time are printed before "
                       "it starts); the strategies share the rest. Render time stays within 1.25x the budget unless "
                       "1 spp per run already costs more (then a warning gives the expected total); loading and "
                       "building the scene come on top")
      ->check(CLI::PositiveNumber)->capture_default_str();
  converge->add_option("--runs", ca.runs, "Independent runs per strategy (different seeds) for the spread")->check(CLI::PositiveNumber)->capture_default_str();
  converge->add_option("-o,--output", ca.out_dir, "Output folder for convergence.csv, convergence.svg, reference.exr")->capture_default_str();
  converge->add_option("--resolution-scale", ca.resolution_scale, "Scale the camera resolution (e.g. 0.25: 512x512 -> 128x128)")->check(CLI::PositiveNumber)->capture_default_str();
  converge->add_option("--reference-spp", ca.reference_spp,
                       "Render the reference with exactly this many spp, even past its share of --budget (its "
                       "estimated time is printed first, with a warning when it does not fit). Default: fit the share")
      ->check(CLI::PositiveNumber);
  converge->add_option("--max-spp", ca.max_spp, "Cap on the samples per pixel of any run")->check(CLI::PositiveNumber)->capture_default_str();
  converge->add_option("--seed", ca.seed, "Base random seed (run r uses seed + 1 + r)")->capture_default_str();
  converge->add_option("--threads", ca.threads, "Worker threads (0: all cores)")->capture_default_str();
  converge->add_option("--accel", ca_accel, "Ray-query backend: embree or bvh")->check(CLI::IsMember({"embree", "bvh"}))->capture_default_str();
  converge->add_flag("--keep-delta-lights", ca.keep_delta_lights, "Keep point/spot/directional/area lights even for strategies without NEE (they then converge to a different image)");
  converge->add_flag("-q,--quiet", ca.quiet, "No progress on stderr");

  ProfileArgs pa;
  std::string profile_accel = "embree";
  auto* profile = app.add_subcommand("profile", "Time and measure the phases of a render (parse, subdivision, "
                                                "build, render), rays per second and peak memory");
  profile->add_option("scene", pa.scene, "Scene file (.xml, .json, .pbrt) or bare mesh (.ply, .obj)")->required();
  profile->add_option("--subdivide", pa.subdivide, "Loop-subdivide the scene's meshes this many times (default: "
                                                  "the scene's own setting)");
  profile->add_option("--accel", profile_accel, "Ray-query backend: embree or bvh")
      ->check(CLI::IsMember({"embree", "bvh"}))->capture_default_str();
  profile->add_option("--spp", pa.spp, "Samples per pixel for the timed render")->check(CLI::PositiveNumber)
      ->capture_default_str();
  profile->add_option("--camera", pa.camera, "Profile the camera with this id (default: the first)");
  profile->add_option("--threads", pa.threads, "Worker threads (0: all cores)")->capture_default_str();
  profile->add_option("--seed", pa.seed, "Random seed")->capture_default_str();
  profile->add_flag("--no-render", pa.no_render, "Stop after building the accelerator");
  profile->add_flag("--json", pa.json, "Print the measurements as JSON instead of a table");
  profile->add_option("--rules", pa.rules, "Whose rules render the profiled camera: kiln or course (default: the scene's)")
      ->check(CLI::IsMember({"kiln", "course"}));
  profile->add_option("--light-sampler", pa.light_sampler, kLightSamplerHelp)
      ->check(CLI::IsMember({"power", "uniform", "bvh"}));

  std::string cb_scene;
  size_t cb_rays = 100000;
  uint64_t cb_seed = 1;
  auto* check = app.add_subcommand("check-bvh", "Compare the in-house BVH with Embree ray by ray (JSON summary; "
                                                "exit 1 when disagreements exceed 1e-5 of the rays)");
  check->add_option("scene", cb_scene, "Scene file")->required();
  check->add_option("--rays", cb_rays, "Camera rays (each adds a bounce and a shadow ray)")->capture_default_str();
  check->add_option("--seed", cb_seed, "Random seed")->capture_default_str();

  std::vector<std::string> merge_parts;
  std::string merge_out;
  auto* merge = app.add_subcommand("merge", "Combine partial renders (--crop / --spp-range parts) into one EXR");
  merge->add_option("parts", merge_parts, "Partial EXR files written by kiln render")->required();
  merge->add_option("-o,--output", merge_out, "Merged EXR to write")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  ra.accel = accel == "bvh" ? AccelKind::Bvh : AccelKind::Embree;
  if (*render) return run_guarded([&] { return cmd_render(ra); });
  if (*info) return run_guarded([&] { return cmd_info(ia); });
  ca.accel = ca_accel == "bvh" ? AccelKind::Bvh : AccelKind::Embree;
  if (*converge) return run_guarded([&] { return cmd_converge(ca); });
  pa.accel = profile_accel == "bvh" ? AccelKind::Bvh : AccelKind::Embree;
  if (*profile) return run_guarded([&] { return cmd_profile(pa); });
  if (*check) return run_guarded([&] { return cmd_check_bvh(cb_scene, cb_rays, cb_seed); });
  if (*merge) return run_guarded([&] { return cmd_merge(merge_parts, merge_out); });
  if (*compare) return run_guarded([&] { return cmd_compare(cmp_image, cmp_ref, cmp_block); });
  return kExitBadInput;
}
