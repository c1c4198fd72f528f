#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "renderer/integrators/aov.h"
#include "renderer/cli/commands.h"
#include "renderer/render/merge.h"
#include "renderer/film/pixel_filter.h"
#include "renderer/render/progressive.h"
#include "renderer/image_io/image_io.h"
#include "renderer/film/tonemap.h"
#include "renderer/world/ray_query.h"
#include "renderer/render/scene_fingerprint.h"
#include "renderer/world/world.h"
#include "renderer/texture/scene_textures.h"
#include "scenes/loader.h"

namespace kiln {
namespace {

std::atomic<bool> g_interrupted{false};
// Samples per pixel of the AOV pass: enough to anti-alias edges, never more than the beauty render takes (at 1 spp
// four AOV rays per pixel would cost ~25% of the render; capped by the total spp, not the part's, so split renders
// agree).
constexpr uint32_t kAovSamplesPerPixel = 4;
extern "C" void on_signal(int) { g_interrupted.store(true); }

std::string stem_of(const std::string& image_name, const std::string& fallback) {
  const std::string stem = std::filesystem::path(image_name).stem().string();
  return stem.empty() ? fallback : stem;
}

// What the scene's textures built: nothing without textures; the OpenImageIO cache only with image textures.
nlohmann::json texture_stats_json(const World& w) {
  if (!w.textures) return {{"built", false}};
  const TextureBuildStats& t = w.textures->stats();
  const TextureCacheStats c = w.textures->cache_stats();
  return {{"built", true},
          {"textures", t.textures},
          {"images", t.images},
          {"procedural", t.procedural},
          {"textured_shape_bindings", t.bindings},
          {"filtered_images", t.filtered},
          {"footprint_bindings", t.footprint_bindings},
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

nlohmann::json world_stats_json(const World& w) {
  const WorldStats& s = w.stats;
  return {{"textures", texture_stats_json(w)},
          {"meshes", s.meshes},
          {"triangles", s.triangles},
          {"spheres", s.spheres},
          {"instances", s.instances},
          {"interface_shapes_left_out", s.interface_shapes},
          {"media",
           {{"built", !w.media.empty()},
            {"homogeneous", s.homogeneous_media},
            {"uniformgrid", s.grid_media},
            {"rgbgrid", s.rgb_grid_media},
            {"nanovdb", s.nanovdb_media},
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
            {"infinite", s.infinite_lights},
            {"environment_map", s.environment_maps}}},
          {"built",
           {{"sphere_geometry", s.sphere_geometry_built},
            {"cone_sampler", s.cone_sampler_built},
            {"light_selector", s.light_selector_built},
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
std::string render_options(const RenderArgs& a) {
  return "clamp=" + std::to_string(a.rules.clamp) + " physical_lights=" + (a.rules.physical_lights ? "1" : "0") +
         " subdivide=" + std::to_string(a.subdivide);
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

}  // namespace

int cmd_merge(const std::vector<std::string>& parts, const std::string& output) {
  const MergeResult r = merge_parts(parts);
  Metadata meta = {{"kiln:version", KILN_VERSION},
                   {"kiln:merged_parts", std::to_string(parts.size())},
                   {"kiln:spp", std::to_string(r.max_samples)},
                   {"kiln:incomplete", r.complete() ? "false" : "true"}};
  meta.insert(meta.end(), r.frame.begin(), r.frame.end());
  if (!r.complete()) meta.emplace_back("kiln:missing", missing_metadata(r.missing));
  write_exr(output, r.image, {}, meta);
  std::printf("%s\n", output.c_str());
  for (const SampleGap& g : r.missing)
    std::fprintf(stderr, "kiln: warning: %s: missing samples %llu:%llu of %llu in pixels %d,%d,%d,%d (render them with %s)\n",
                 output.c_str(), (unsigned long long)g.first, (unsigned long long)g.last, (unsigned long long)r.spp_total,
                 g.x0, g.x1, g.y0, g.y1, g.to_args().c_str());
  if (!r.complete()) std::fprintf(stderr, "kiln: warning: %s is incomplete (kiln:incomplete = true)\n", output.c_str());
  return 0;
}

int cmd_render(const RenderArgs& args) {
  const auto t_start = std::chrono::steady_clock::now();
  std::unique_ptr<tbb::global_control> threads;
  if (args.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(args.threads));

  if (args.filter) (void)parse_pixel_filter(*args.filter);  // bad input is reported before any work
  if (args.adaptive && args.spp_range)
    throw Error("--adaptive", "", "cannot be combined with --spp-range: a pixel's stopping decision needs all its "
                                  "samples from index 0");

  LoadOptions lo;
  lo.subdivide = args.subdivide;
  SceneFingerprint fingerprint;  // identifies the scene in the metadata of split renders (renderer/render/merge.h)
  SceneDesc scene = load_scene_fingerprinted(args.scene, lo, fingerprint);  // its meshes are handed to the world
  const double parse_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  if (scene.cameras.empty()) throw Error(args.scene, "", "scene has no camera");
  std::vector<const CameraDesc*> cameras;
  for (const CameraDesc& c : scene.cameras)
    if (!args.camera || c.id == *args.camera) cameras.push_back(&c);
  if (cameras.empty()) throw Error(args.scene, "", "no camera with id '" + *args.camera + "'");

  const SceneRules rules = resolve_rules(scene, args.rules);
  WorldOptions wo;
  wo.accel = args.accel;
  wo.ellipsoid_pdf = ellipsoid_pdf(rules, args.rules);
  wo.env_map_sampling = env_map_sampling(rules, args.rules);
  const uint32_t aov_flags = args.aovs ? parse_aovs(*args.aovs) : 0u;
  const auto world = build_world_taking_meshes(scene, wo);
  if (!args.quiet) {
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "kiln: warning: %s: %s\n", args.scene.c_str(), w.c_str());
    for (const std::string& w : world->warnings) std::fprintf(stderr, "kiln: warning: %s: %s\n", args.scene.c_str(), w.c_str());
    for (const std::string& u : scene.unsupported)
      std::fprintf(stderr, "kiln: warning: %s: not rendered yet: %s\n", args.scene.c_str(), u.c_str());
  }

  g_interrupted.store(false);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  nlohmann::json stats;
  stats["scene"] = args.scene;
  stats["kiln_version"] = KILN_VERSION;
  stats["parse_seconds"] = parse_seconds;
  stats["world"] = world_stats_json(*world);
  stats["cameras"] = nlohmann::json::array();
  bool interrupted = false;
  const bool is_part = args.crop || args.spp_range;

  for (const CameraDesc* cd : cameras) {
    const Camera camera(*cd);
    const IntegratorSettings settings =
        camera_settings(*cd, scene, rules, args.rules, args.all_features ? kFeatureAll : world->features);
    const uint32_t spp = args.spp.value_or(uint32_t(std::max(1, cd->num_samples)));
    uint32_t first = 0, last = spp;
    if (args.spp_range) std::tie(first, last) = parse_spp_range(*args.spp_range);
    std::optional<Crop> crop;
    if (args.crop) crop = parse_crop(*args.crop, camera.width(), camera.height());
    RenderOptions ro;
    ro.crop = crop;
    ro.seed = args.seed;
    ro.spp_total = spp;
    ro.progress = !args.quiet;
    ro.cancel = &g_interrupted;
    ro.reverse_tile_order = args.reverse_tiles;
    ro.filter = pixel_filter_for(*cd, args.filter);
    if (args.adaptive) ro.adaptive = AdaptiveSampling{*args.adaptive, args.adaptive_min_spp};
    Film film(camera.width(), camera.height());
    if (!args.quiet)
      std::fprintf(stderr, "kiln: camera %s: %dx%d, %u spp, %s: %s\n", cd->id.c_str(), camera.width(), camera.height(),
                   spp, rules_name(rules), settings.describe().c_str());
    RenderStats rs;
    std::optional<ErrorStats> final_error;
    std::string csv_path;
    if (args.time_limit || args.reference) {
      // Waves of doubling spp: error against the reference after each, and/or stop before the budget runs out.
      if (args.spp_range || args.crop) throw Error("--time-limit/--reference", "", "cannot be combined with --crop or --spp-range");
      Image reference;
      ProgressiveOptions po;
      po.time_limit_seconds = args.time_limit;
      if (args.reference) {
        reference = read_exr(*args.reference).rgb;
        po.reference = &reference;
      }
      std::string csv = wave_csv_header();
      po.on_wave = [&](const WaveReport& w) { csv += wave_csv_line(w); };
      const ProgressiveResult pr = render_progressive(*world, camera, settings, ro, spp, po, film);
      rs = pr.stats;
      last = pr.spp;
      final_error = pr.final_error;
      if (args.reference) {
        csv_path = (std::filesystem::path(args.out_dir) / (stem_of(cd->image_name, "camera" + cd->id) + ".convergence.csv")).string();
        std::filesystem::create_directories(args.out_dir);
        std::ofstream(csv_path) << csv;
      }
      if (!args.quiet && pr.stopped_by_time_limit)
        std::fprintf(stderr, "kiln: time limit reached after %u spp\n", pr.spp);
    } else {
      rs = render_samples(*world, camera, settings, ro, first, last, film);
    }
    interrupted = rs.cancelled;
    // A part of a split frame (--crop / --spp-range) cut short holds unequal sample counts that `kiln merge`
    // cannot weigh: it is not written, so the merge sees the range as missing and a re-run fills it.
    if (interrupted && is_part) break;

    const std::string stem = stem_of(cd->image_name, "camera" + cd->id);
    const std::string exr = (std::filesystem::path(args.out_dir) / (stem + ".exr")).string();
    const std::string png = (std::filesystem::path(args.out_dir) / (stem + ".png")).string();
    const Image full = film.mean();
    const SampleCounts counts = sample_counts(film, crop.value_or(Crop{0, camera.width(), 0, camera.height()}));
    std::vector<AovLayer> aovs;
    double aov_seconds = 0.0;
    if (aov_flags) {
      const auto t_aov = std::chrono::steady_clock::now();
      aovs = render_aovs(*world, camera, aov_flags, film, ro, std::min(kAovSamplesPerPixel, spp));
      aov_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_aov).count();
    }
    const Image img = crop ? crop_image(full, *crop) : full;
    if (crop) aovs = crop_layers(std::move(aovs), camera.width(), *crop);
    std::optional<DataWindow> window;
    if (crop) window = DataWindow{crop->x0, crop->y0, camera.width(), camera.height()};
    Metadata meta = {{"kiln:version", KILN_VERSION},
                     {"kiln:scene", args.scene},
                     {"kiln:camera", cd->id},
                     {"kiln:spp", std::to_string(last - first)},
                     {"kiln:spp_first", std::to_string(first)},
                     {"kiln:spp_last", std::to_string(last)},
                     {"kiln:spp_total", std::to_string(spp)},
                     {"kiln:scene_hash", fingerprint.hash},
                     {"kiln:scene_files", std::to_string(fingerprint.files)},
                     {"kiln:seed", std::to_string(args.seed)},
                     {"kiln:rules", rules_name(rules)},
                     {"kiln:integrator", settings.describe()},
                     {"kiln:render_options", render_options(args)},
                     {"kiln:render_seconds", std::to_string(rs.seconds)},
                     {"kiln:filter", describe_pixel_filter(ro.filter)},
                     {"kiln:mean_spp", std::to_string(counts.mean)},
                     {"kiln:incomplete", rs.cancelled ? "true" : "false"}};
    if (ro.adaptive) meta.emplace_back("kiln:adaptive_threshold", std::to_string(ro.adaptive->threshold));
    if (final_error) {
      meta.emplace_back("kiln:reference", *args.reference);
      meta.emplace_back("kiln:mse", std::to_string(final_error->mse));
      meta.emplace_back("kiln:relmse", std::to_string(final_error->rel_mse));
      meta.emplace_back("kiln:rmse", std::to_string(final_error->rmse));
    }
    write_exr(exr, img, aovs, meta, window);
    write_png(png, to_ldr(img, preview_for_camera(*cd, scene)), img.width(), img.height());

    const double query_seconds = double(rs.rays.query_cycles()) / tsc_frequency();
    const double query_share = query_seconds / std::max(1e-9, rs.seconds * double(tbb::this_task_arena::max_concurrency()));
    const double mrays = double(rs.rays.total()) / std::max(rs.seconds, 1e-9) / 1e6;
    if (rs.has_nan && !args.quiet)
      std::fprintf(stderr, "kiln: warning: %llu non-finite samples dropped (first at pixel %d,%d sample %llu)\n",
                   (unsigned long long)rs.rays.nan_samples, rs.nan_x, rs.nan_y, (unsigned long long)rs.nan_sample);
    if (!args.quiet)
      std::fprintf(stderr,
                   "kiln: %.2fs, %.2f Mrays/s (primary %llu, shadow %llu, indirect %llu), %.0f%% of thread time in "
                   "ray queries\n",
                   rs.seconds, mrays, (unsigned long long)rs.rays.primary, (unsigned long long)rs.rays.shadow,
                   (unsigned long long)rs.rays.indirect, 100.0 * query_share);
    if (!args.quiet && !world->media.empty())
      std::fprintf(stderr, "kiln: media: %llu tracked segments, %.2f steps per segment, majorant efficiency %.2f\n",
                   (unsigned long long)rs.rays.media.rays, rs.rays.media.steps_per_ray(),
                   rs.rays.media.majorant_efficiency());

    std::printf("%s\n%s\n", exr.c_str(), png.c_str());
    std::fflush(stdout);

    nlohmann::json cam = {{"id", cd->id},
                                {"exr", exr},
                                {"png", png},
                                {"width", camera.width()},
                                {"height", camera.height()},
                                {"spp", spp},
                                {"rules", rules_name(rules)},
                                {"integrator", settings.describe()},
                                {"render_seconds", rs.seconds},
                                {"aov_seconds", aov_seconds},
                                {"rays", {{"primary", rs.rays.primary}, {"shadow", rs.rays.shadow}, {"indirect", rs.rays.indirect}}},
                                {"mrays_per_second", mrays},
                                {"ray_query_share", query_share},
                                {"nan_samples", rs.rays.nan_samples},
                                {"filter", describe_pixel_filter(ro.filter)},
                                {"mean_spp", counts.mean},
                                {"incomplete", rs.cancelled}};
    if (ro.adaptive)
      cam["adaptive"] = {{"threshold", ro.adaptive->threshold}, {"min_spp", ro.adaptive->min_samples()},
                         {"converged_fraction", counts.converged_fraction}};
    if (!world->media.empty())
      cam["media"] = media_stats_json(rs.rays.media);
    if (final_error)
      cam["error"] = {{"reference", *args.reference}, {"mse", final_error->mse}, {"relmse", final_error->rel_mse},
                      {"rmse", final_error->rmse}, {"csv", csv_path}};
    stats["cameras"].push_back(cam);
    if (interrupted) break;
  }
  stats["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  if (args.stats_path) {
    const std::string tmp = *args.stats_path + ".tmp";
    {
      std::ofstream f(tmp);
      if (!f) throw Error(*args.stats_path, "", "cannot write stats file");
      f << stats.dump(2) << "\n";
    }
    std::filesystem::rename(tmp, *args.stats_path);
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (interrupted) {
    std::fprintf(stderr, is_part ? "kiln: interrupted; the part was not written\n"
                                 : "kiln: interrupted; wrote the samples so far (marked incomplete)\n");
    return 130;
  }
  return 0;
}

}  // namespace kiln
