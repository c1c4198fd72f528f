#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "renderer/analysis/error_curve.h"
#include "renderer/cli/commands.h"
#include "renderer/cli/interrupt.h"
#include "renderer/film/pixel_filter.h"
#include "renderer/film/tonemap.h"
#include "renderer/image_io/image_io.h"
#include "renderer/integrators/aov.h"
#include "renderer/render/progressive.h"
#include "renderer/render/scene_fingerprint.h"
#include "renderer/texture/scene_textures.h"
#include "renderer/world/ray_query.h"
#include "renderer/world/world.h"
#include "scenes/loader.h"

namespace kiln {
namespace {

// Samples per pixel of the AOV pass: enough to anti-alias edges, never more than the beauty render takes (at 1 spp
// four AOV rays per pixel would cost ~25% of the render; capped by the total spp, not the part's, so split renders
// agree).

std::string stem_of(const std::string& image_name, const std::string& fallback) {
  const std::string stem = std::filesystem::path(image_name).stem().string();
  return stem.empty() ? fallback : stem;
}

// What the scene's textures built: nothing without textures; the OpenImageIO cache only with image textures.
nlohmann::json texture_stats_json(const World& w) {
  if (!w.textures) return {{"built", false}};
  const TextureBuildStats t = w.textures->stats();
  const TextureCacheStats c = w.textures->cache_stats();
  return {{"built", true},
          {"textures", t.textures},
          {"images", t.images},
          {"procedural", t.procedural},
          {"textured_shape_bindings", t.bindings},
          {"filtered_images", t.filtered},
          {"footprint_bindings", t.footprint_bindings},
          {"pbrt_textures_defined", t.pbrt.defined},
          {"pbrt_textures_used", t.pbrt.compiled},
          {"pbrt_texture_images", t.pbrt.images},
          {"per_hit_materials", t.textured_materials},
          {"texture_system", t.texture_system_built},
          {"cache_limit_mb", t.cache_limit_mb},
          {"cache_memory_bytes", c.memory_used},
          {"file_bytes_read", c.bytes_read},
          {"files", c.files}};
}

// Tracking through media: segments tracked (camera, bounce and light rays inside a medium), tentative collisions
// per segment, and the mean sigma_t / sigma_maj at them.
nlohmann::json media_stats_json(const TrackingCounters& t) {
  return {{"tracked_segments", t.rays},
          {"collisions", t.collisions},
          {"steps_per_segment", t.steps_per_ray()},
          {"majorant_efficiency", t.majorant_efficiency()}};
}

// Which light sampler next event estimation uses; for the hierarchy its size and build time.
nlohmann::json light_sampler_json(const WorldStats& s) {
  if (!s.light_sampler_built) return {{"built", false}};
  const LightSamplerStats& l = s.light_sampler;
  nlohmann::json j = {{"built", true}, {"kind", light_sampler_name(l.kind)}, {"build_seconds", l.build_seconds}};
  if (l.kind == LightSamplerKind::Bvh) {
    j["emitters"] = l.emitters;
    j["nodes"] = l.nodes;
    j["depth"] = l.depth;
    j["infinite_lights"] = l.infinite_lights;
    j["bytes"] = l.bytes;
  }
  return j;
}

nlohmann::json world_stats_json(const World& w) {
  const WorldStats& s = w.stats;
  return {{"textures", texture_stats_json(w)},
          {"meshes", s.meshes},
          {"triangles", s.triangles},
          {"spheres", s.spheres},
          {"quadrics", s.quadrics},
          {"instances", s.instances},
          {"alpha_shapes", s.alpha_shapes},
          {"interface_shapes_left_out", s.interface_shapes},
          {"media",
           {{"built", !w.media.empty()},
            {"homogeneous", s.homogeneous_media},
            {"uniformgrid", s.grid_media},
            {"rgbgrid", s.rgb_grid_media},
            {"nanovdb", s.nanovdb_media},
            {"cloud", s.cloud_media},
            {"boundaries", s.medium_boundaries},
            {"majorant_voxels", s.majorant_voxels},
            {"grid_bytes", s.medium_grid_bytes},
            {"media", s.media}}},
          {"materials", s.materials},
          {"compiled_materials", s.compiled_materials},
          {"lights",
           {{"point", s.point_lights},
            {"spot", s.spot_lights},
            {"directional", s.directional_lights},
            {"area", s.area_lights},
            {"mesh", s.mesh_lights},
            {"sphere", s.sphere_lights},
            {"quadric", s.quadric_lights},
            {"infinite", s.infinite_lights},
            {"environment_map", s.environment_maps}}},
          {"built",
           {{"sphere_geometry", s.sphere_geometry_built},
            {"cone_sampler", s.cone_sampler_built},
            {"light_sampler", light_sampler_json(s)},
            // Motion blur: time-varying geometry and a shutter-time sample per camera sample, only when shapes move.
            {"moving_shapes", s.moving_shapes},
            {"time_sample", s.moving_shapes > 0},
            {"accelerator", w.accel->stats().name}}},
          {"features", describe_features(w.features)},
          {"accel_build_seconds", w.accel->stats().build_seconds},
          {"accel_bytes", w.accel->stats().bytes},
          {"world_build_seconds", s.build_seconds},
          {"unsupported", w.unsupported}};
}

// The options besides the integrator that change a frame's pixels, so that `kiln merge` refuses parts rendered
// with different ones.
std::string render_options(const RenderArgs& a, const World& w) {
  return "clamp=" + std::to_string(a.rules.clamp) + " physical_lights=" + (a.rules.physical_lights ? "1" : "0") +
         " subdivide=" + std::to_string(a.subdivide) + " light_sampler=" + light_sampler_name(w.stats.light_sampler.kind);
}

Crop parse_crop(const std::string& text, int width, int height) {
  Crop c;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &c.x0, &c.x1, &c.y0, &c.y1, &extra) != 4)
    throw Error("--crop", "", "expected x0,x1,y0,y1 (pixels, x1 and y1 exclusive), got '" + text + "'");
  if (c.x0 < 0 || c.y0 < 0 || c.x1 > width || c.y1 > height || c.x0 >= c.x1 || c.y0 >= c.y1)
    throw Error("--crop", "", "'" + text + "' is empty or outside the " + std::to_string(width) + "x" +
                                  std::to_string(height) + " frame");
  return c;
}

std::pair<uint32_t, uint32_t> parse_spp_range(const std::string& text) {
  unsigned long long a = 0, b = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%llu:%llu%c", &a, &b, &extra) != 2 || a >= b || b > 0xffffffffull)
    throw Error("--spp-range", "", "expected FIRST:LAST with FIRST < LAST, got '" + text + "'");
  return {uint32_t(a), uint32_t(b)};
}

Image crop_image(const Image& img, const Crop& c) {
  Image out(c.x1 - c.x0, c.y1 - c.y0);
  for (int y = c.y0; y < c.y1; ++y)
    for (int x = c.x0; x < c.x1; ++x) out.at(x - c.x0, y - c.y0) = img.at(x, y);
  return out;
}

std::vector<AovLayer> crop_layers(std::vector<AovLayer> layers, int width, const Crop& c) {
  for (AovLayer& l : layers) {
    const size_t nc = l.channels.size();
    std::vector<float> d;
    d.reserve(size_t(c.x1 - c.x0) * size_t(c.y1 - c.y0) * nc);
    for (int y = c.y0; y < c.y1; ++y)
      for (int x = c.x0; x < c.x1; ++x)
        for (size_t k = 0; k < nc; ++k) d.push_back(l.data[(size_t(y) * size_t(width) + size_t(x)) * nc + k]);
    l.data = std::move(d);
  }
  return layers;
}

struct SampleCounts {
  double mean = 0;                // samples per pixel, averaged over the rendered pixels
  double converged_fraction = 0;  // pixels stopped by adaptive sampling
};

SampleCounts sample_counts(const Film& film, const Crop& c) {
  SampleCounts s;
  for (int y = c.y0; y < c.y1; ++y)
    for (int x = c.x0; x < c.x1; ++x) {
      s.mean += film.at(x, y).n;
      s.converged_fraction += film.at(x, y).converged ? 1.0 : 0.0;
    }
  const double npx = double(c.x1 - c.x0) * double(c.y1 - c.y0);
  s.mean /= npx;
  s.converged_fraction /= npx;
  return s;
}


// The scene loaded for a render: its description, identity, rule set, world, and the cameras to render.
struct LoadedScene {
  SceneDesc scene;
  SceneFingerprint fingerprint;  // identifies the scene in the metadata of split renders (renderer/render/merge.h)
  SceneRules rules = SceneRules::Kiln;
  std::unique_ptr<World> world;
  std::vector<size_t> cameras;  // indices into scene.cameras
  double parse_seconds = 0;
};

// Bad option combinations are reported before any work.
void check_render_args(const RenderArgs& args) {
  if (args.filter) (void)parse_pixel_filter(*args.filter);
  if (args.adaptive && args.spp_range)
    throw Error("--adaptive", "", "cannot be combined with --spp-range: a pixel's stopping decision needs all its "
                                  "samples from index 0");
}

LoadedScene load_for_render(const RenderArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  LoadedScene l;
  LoadOptions lo;
  lo.subdivide = args.subdivide;
  l.scene = load_scene_fingerprinted(args.scene, lo, l.fingerprint);  // its meshes are handed to the world
  l.parse_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (l.scene.cameras.empty()) throw Error(args.scene, "", "scene has no camera");
  for (size_t i = 0; i < l.scene.cameras.size(); ++i)
    if (!args.camera || l.scene.cameras[i].id == *args.camera) l.cameras.push_back(i);
  if (l.cameras.empty()) throw Error(args.scene, "", "no camera with id '" + *args.camera + "'");
  l.rules = resolve_rules(l.scene, args.rules);
  WorldOptions wo;
  wo.accel = args.accel;
  wo.ellipsoid_pdf = ellipsoid_pdf(l.rules, args.rules);
  wo.env_map_sampling = env_map_sampling(l.rules, args.rules);
  wo.light_sampler = light_sampler_kind(l.rules, args.rules);
  if (args.aovs) (void)parse_aovs(*args.aovs);  // a bad name fails before the world is built
  l.world = build_world_taking_meshes(l.scene, wo);
  return l;
}

void print_scene_warnings(const RenderArgs& args, const LoadedScene& l) {
  const char* path = args.scene.c_str();
  for (const std::string& w : l.scene.warnings) std::fprintf(stderr, "kiln: warning: %s: %s\n", path, w.c_str());
  for (const std::string& w : l.world->warnings) std::fprintf(stderr, "kiln: warning: %s: %s\n", path, w.c_str());
  for (const std::string& u : l.scene.unsupported)
    std::fprintf(stderr, "kiln: warning: %s: not rendered yet: %s\n", path, u.c_str());
}

// One camera's render as the command line asks for it.
struct CameraJob {
  const CameraDesc& desc;
  Camera camera;
  IntegratorSettings settings;
  uint32_t spp = 1;              // the frame's samples per pixel
  uint32_t first = 0, last = 1;  // the sample range rendered (--spp-range)
  std::optional<Crop> crop;
  RenderOptions options;
  uint32_t aovs = 0;  // AovFlag bits (--aov)
  Film film;

  CameraJob(const RenderArgs& args, const LoadedScene& l, const CameraDesc& cd, const std::atomic<bool>& cancel)
      : desc(cd),
        camera(cd),
        settings(camera_settings(cd, l.scene, l.rules, args.rules,
                                 args.all_features ? kFeatureAll : l.world->features)),
        spp(args.spp.value_or(uint32_t(std::max(1, cd.num_samples)))),
        last(spp),
        film(camera.width(), camera.height()) {
    if (args.spp_range) std::tie(first, last) = parse_spp_range(*args.spp_range);
    if (args.crop) crop = parse_crop(*args.crop, camera.width(), camera.height());
    options.crop = crop;
    options.seed = args.seed;
    options.spp_total = spp;
    options.progress = !args.quiet;
    options.cancel = &cancel;
    options.reverse_tile_order = args.reverse_tiles;
    options.filter = pixel_filter_for(cd, args.filter);
    if (args.adaptive) options.adaptive = AdaptiveSampling{*args.adaptive, args.adaptive_min_spp};
    // A scene's own request for AOV layers (pbrt Film "gbuffer"): all of them, unless --aov chose.
    aovs = args.aovs ? parse_aovs(*args.aovs) : (cd.aov_layers ? parse_aovs("all") : 0u);
    if (aovs & kAovSurface) film.keep_surfaces();  // the samples record what they see (renderer/integrators/aov.h)
  }
  std::string stem() const { return stem_of(desc.image_name, "camera" + desc.id); }
  Crop region() const { return crop.value_or(Crop{0, camera.width(), 0, camera.height()}); }
};

struct FrameResult {
  RenderStats stats;
  std::optional<ErrorStats> final_error;  // --reference
  std::string csv_path;                   // --reference: the error after every wave
};

// Waves of doubling spp (renderer/render/progressive.h): the error against the reference after each, and/or a stop
// before the time budget runs out. job.last becomes the samples the waves completed.
FrameResult render_in_waves(const RenderArgs& args, const LoadedScene& l, CameraJob& job) {
  if (args.spp_range || args.crop)
    throw Error("--time-limit/--reference", "", "cannot be combined with --crop or --spp-range");
  ProgressiveOptions po;
  po.time_limit_seconds = args.time_limit;
  FrameResult r;
  ProgressiveResult pr;
  if (args.reference) {
    const Image reference = read_exr(*args.reference).rgb;
    const ErrorCurve curve =
        render_error_curve(*l.world, job.camera, job.settings, job.options, job.spp, reference, po, job.film);
    pr = curve.render;
    r.final_error = curve.final_error;
    std::string csv = wave_csv_header();
    for (const MeasuredWave& w : curve.waves) csv += wave_csv_line(w);
    r.csv_path = (std::filesystem::path(args.out_dir) / (job.stem() + ".convergence.csv")).string();
    std::filesystem::create_directories(args.out_dir);
    std::ofstream(r.csv_path) << csv;
  } else {
    pr = render_progressive(*l.world, job.camera, job.settings, job.options, job.spp, po, job.film);
  }
  r.stats = pr.stats;
  job.last = pr.spp;
  if (!args.quiet && pr.stopped_by_time_limit) std::fprintf(stderr, "kiln: time limit reached after %u spp\n", pr.spp);
  return r;
}

FrameResult render_frame(const RenderArgs& args, const LoadedScene& l, CameraJob& job) {
  if (!args.quiet)
    std::fprintf(stderr, "kiln: camera %s: %dx%d, %u spp, %s: %s\n", job.desc.id.c_str(), job.camera.width(),
                 job.camera.height(), job.spp, rules_name(l.rules), job.settings.describe().c_str());
  if (args.time_limit || args.reference) return render_in_waves(args, l, job);
  FrameResult r;
  r.stats = render_samples(*l.world, job.camera, job.settings, job.options, job.first, job.last, job.film);
  return r;
}

// What a frame's EXR says about how it was made (`kiln merge` checks the scene, the options and the sample ranges).
Metadata frame_metadata(const RenderArgs& args, const LoadedScene& l, const CameraJob& job, const FrameResult& r,
                        const SampleCounts& counts) {
  Metadata meta = {{"kiln:version", KILN_VERSION},
                   {"kiln:scene", args.scene},
                   {"kiln:camera", job.desc.id},
                   {"kiln:spp", std::to_string(job.last - job.first)},
                   {"kiln:spp_first", std::to_string(job.first)},
                   {"kiln:spp_last", std::to_string(job.last)},
                   {"kiln:spp_total", std::to_string(job.spp)},
                   {"kiln:scene_hash", l.fingerprint.hash},
                   {"kiln:scene_files", scene_files_metadata(l.fingerprint)},
                   {"kiln:seed", std::to_string(args.seed)},
                   {"kiln:rules", rules_name(l.rules)},
                   {"kiln:integrator", job.settings.describe()},
                   {"kiln:render_options", render_options(args, *l.world)},
                   {"kiln:render_seconds", std::to_string(r.stats.seconds)},
                   {"kiln:filter", describe_pixel_filter(job.options.filter)},
                   {"kiln:mean_spp", std::to_string(counts.mean)},
                   {"kiln:incomplete", r.stats.cancelled ? "true" : "false"}};
  if (job.options.adaptive)
    meta.emplace_back("kiln:adaptive_threshold", std::to_string(job.options.adaptive->threshold));
  if (r.final_error) {
    meta.emplace_back("kiln:reference", *args.reference);
    meta.emplace_back("kiln:mse", std::to_string(r.final_error->mse));
    meta.emplace_back("kiln:relmse", std::to_string(r.final_error->rel_mse));
    meta.emplace_back("kiln:rmse", std::to_string(r.final_error->rmse));
  }
  return meta;
}

struct WrittenFrame {
  std::string exr, png;
  SampleCounts counts;
};

// The frame's EXR (with its AOV layers; a crop as a data window) and PNG preview.
WrittenFrame write_frame(const RenderArgs& args, const LoadedScene& l, const CameraJob& job, const FrameResult& r) {
  WrittenFrame out;
  out.exr = (std::filesystem::path(args.out_dir) / (job.stem() + ".exr")).string();
  out.png = (std::filesystem::path(args.out_dir) / (job.stem() + ".png")).string();
  const Image full = job.film.mean();
  out.counts = sample_counts(job.film, job.region());
  std::vector<AovLayer> aovs = aov_layers(job.film, job.aovs);
  const Image img = job.crop ? crop_image(full, *job.crop) : full;
  if (job.crop) aovs = crop_layers(std::move(aovs), job.camera.width(), *job.crop);
  std::optional<DataWindow> window;
  if (job.crop) window = DataWindow{job.crop->x0, job.crop->y0, job.camera.width(), job.camera.height()};
  write_exr(out.exr, img, aovs, frame_metadata(args, l, job, r, out.counts), window);
  write_png(out.png, to_ldr(img, preview_for_camera(job.desc, l.scene)), img.width(), img.height());
  return out;
}

// A render does not time its ray queries (kiln profile does): it reports the ray rate alone.
struct RayRates {
  double mrays = 0;  // millions of rays per second
};

RayRates ray_rates(const RenderStats& rs) { return {double(rs.rays.total()) / std::max(rs.seconds, 1e-9) / 1e6}; }

void print_frame_summary(const RenderStats& rs, const RayRates& rates, bool media) {
  if (rs.has_nan)
    std::fprintf(stderr, "kiln: warning: %llu non-finite samples dropped (first at pixel %d,%d sample %llu)\n",
                 (unsigned long long)rs.rays.nan_samples, rs.nan_x, rs.nan_y, (unsigned long long)rs.nan_sample);
  std::fprintf(stderr,
               "kiln: %.2fs, %.2f Mrays/s (primary %llu, shadow %llu, indirect %llu)\n", rs.seconds, rates.mrays,
               (unsigned long long)rs.rays.primary, (unsigned long long)rs.rays.shadow,
               (unsigned long long)rs.rays.indirect);
  if (media)
    std::fprintf(stderr, "kiln: media: %llu tracked segments, %.2f steps per segment, majorant efficiency %.2f\n",
                 (unsigned long long)rs.rays.media.rays, rs.rays.media.steps_per_ray(),
                 rs.rays.media.majorant_efficiency());
}

nlohmann::json camera_json(const RenderArgs& args, const LoadedScene& l, const CameraJob& job, const FrameResult& r,
                           const WrittenFrame& out, const RayRates& rates) {
  const RenderStats& rs = r.stats;
  nlohmann::json cam = {{"id", job.desc.id},
                        {"exr", out.exr},
                        {"png", out.png},
                        {"width", job.camera.width()},
                        {"height", job.camera.height()},
                        {"spp", job.spp},
                        {"rules", rules_name(l.rules)},
                        {"integrator", job.settings.describe()},
                        {"render_seconds", rs.seconds},
                        {"rays",
                         {{"primary", rs.rays.primary}, {"shadow", rs.rays.shadow}, {"indirect", rs.rays.indirect}}},
                        {"mrays_per_second", rates.mrays},
                        {"nan_samples", rs.rays.nan_samples},
                        {"filter", describe_pixel_filter(job.options.filter)},
                        {"mean_spp", out.counts.mean},
                        {"incomplete", rs.cancelled}};
  if (job.options.adaptive)
    cam["adaptive"] = {{"threshold", job.options.adaptive->threshold}, {"min_spp", job.options.adaptive->min_samples()},
                       {"converged_fraction", out.counts.converged_fraction}};
  if (!l.world->media.empty()) cam["media"] = media_stats_json(rs.rays.media);
  if (r.final_error)
    cam["error"] = {{"reference", *args.reference}, {"mse", r.final_error->mse}, {"relmse", r.final_error->rel_mse},
                    {"rmse", r.final_error->rmse}, {"csv", r.csv_path}};
  return cam;
}

// Written under a temporary name and moved into place, so a reader never sees half a file.
void write_stats_file(const std::string& path, const nlohmann::json& stats) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    if (!f) throw Error(path, "", "cannot write stats file");
    f << stats.dump(2) << "\n";
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

int cmd_render(const RenderArgs& args) {
  const auto t_start = std::chrono::steady_clock::now();
  std::unique_ptr<tbb::global_control> threads;
  if (args.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(args.threads));
  check_render_args(args);
  const LoadedScene l = load_for_render(args);
  if (!args.quiet) print_scene_warnings(args, l);

  const InterruptGuard interrupt;
  nlohmann::json stats = {{"scene", args.scene},
                          {"kiln_version", KILN_VERSION},
                          {"parse_seconds", l.parse_seconds},
                          {"world", world_stats_json(*l.world)},
                          {"cameras", nlohmann::json::array()}};
  const bool is_part = args.crop || args.spp_range;
  bool interrupted = false;
  for (const size_t c : l.cameras) {
    CameraJob job(args, l, l.scene.cameras[c], interrupt.flag());
    const FrameResult r = render_frame(args, l, job);
    interrupted = r.stats.cancelled;
    // A part of a split frame (--crop / --spp-range) cut short holds unequal sample counts that `kiln merge`
    // cannot weigh: it is not written, so the merge sees the range as missing and a re-run fills it.
    if (interrupted && is_part) break;
    const WrittenFrame out = write_frame(args, l, job, r);
    const RayRates rates = ray_rates(r.stats);
    if (!args.quiet) print_frame_summary(r.stats, rates, !l.world->media.empty());
    std::printf("%s\n%s\n", out.exr.c_str(), out.png.c_str());
    std::fflush(stdout);
    stats["cameras"].push_back(camera_json(args, l, job, r, out, rates));
    if (interrupted) break;
  }
  stats["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  if (args.stats_path) write_stats_file(*args.stats_path, stats);
  if (interrupted) {
    std::fprintf(stderr, is_part ? "kiln: interrupted; the part was not written\n"
                                 : "kiln: interrupted; wrote the samples so far (marked incomplete)\n");
    return 130;
  }
  return 0;
}

}  // namespace kiln
