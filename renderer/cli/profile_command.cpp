#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "renderer/cli/profile.h"
#include "renderer/integrators/integrator.h"
#include "renderer/integrators/rules.h"
#include "renderer/render/render.h"
#include "renderer/world/ray_query.h"
#include "renderer/world/world.h"
#include "scenes/loader.h"
#include "scenes/subdivision.h"
#include "scenes/xml_loader.h"

namespace kiln {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double load_average() {
  std::ifstream f("/proc/loadavg");
  double l = 0;
  f >> l;
  return l;
}

constexpr size_t kKiB = 1024;
constexpr double kMiB = 1024.0 * 1024.0;
// A "Name:   1234 kB" line of /proc/self/status, in bytes; 0 when unavailable.
size_t proc_status_bytes(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(f, line))
    if (line.rfind(prefix, 0) == 0) return size_t(std::stoull(line.substr(prefix.size()))) * kKiB;
  return 0;
}

size_t current_rss() { return proc_status_bytes("VmRSS"); }

// The peak resident set so far (or since the last reset_peak_rss).
size_t peak_rss(std::string* source = nullptr) {
  if (const size_t hwm = proc_status_bytes("VmHWM")) {
    if (source) *source = "VmHWM";
    return hwm;
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  if (source) *source = "ru_maxrss";
  return size_t(ru.ru_maxrss) * kKiB;  // kilobytes on Linux
}

// Writing 5 to clear_refs resets VmHWM to the current RSS (Linux >= 4.0), so each phase gets its own peak.
bool reset_peak_rss() {
  std::ofstream f("/proc/self/clear_refs");
  if (!f) return false;
  f << "5";
  f.flush();
  return f.good();
}

template <typename T>
size_t vector_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

size_t scene_desc_bytes(const SceneDesc& s) {
  size_t b = 0;
  for (const MeshDesc& m : s.meshes)
    b += vector_bytes(m.positions) + vector_bytes(m.indices) + vector_bytes(m.normals) + vector_bytes(m.uvs);
  return b;
}

size_t world_geometry_bytes(const WorldGeometry& g) {
  size_t b = 0;
  for (const TriangleMesh& m : g.meshes) b += vector_bytes(m.p) + vector_bytes(m.idx);
  for (const TriangleMesh& m : g.prototypes) b += vector_bytes(m.p) + vector_bytes(m.idx);
  return b;
}


// Loads without subdividing, so that subdivision is timed on its own; --subdivide N overrides the levels exactly
// as `kiln render --subdivide` does (scenes/loader.h).
SceneDesc load_unsubdivided(const ProfileArgs& args) {
  LoadOptions lo;
  lo.subdivide = args.subdivide;
  lo.defer_subdivision = true;
  return load_scene(args.scene, lo);
}

RayKindStats ray_kind(uint64_t count, double seconds, uint64_t query_cycles) {
  const double query_seconds = double(query_cycles) / tsc_frequency();
  return {count, double(count) / std::max(seconds, 1e-9) / 1e6, double(count) / std::max(query_seconds, 1e-9) / 1e6};
}

}  // namespace

ProfileReport run_profile(const ProfileArgs& args) {
  const auto t_start = Clock::now();
  std::unique_ptr<tbb::global_control> threads;
  if (args.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(args.threads));

  ProfileReport r;
  r.scene = args.scene;
  r.subdivide = args.subdivide;
  r.threads = int(tbb::this_task_arena::max_concurrency());
  if (args.threads > 0) r.threads = std::min(r.threads, args.threads);
  r.peak_reset_supported = reset_peak_rss();
  r.baseline_rss = current_rss();
  if (r.baseline_rss == 0) r.baseline_rss = peak_rss();
  auto phase_peak = [&] {
    const size_t p = peak_rss(&r.peak_source);
    r.peak_rss = std::max(r.peak_rss, p);
    if (r.peak_reset_supported) reset_peak_rss();
    return p;
  };

  r.load_average = load_average();
  auto t = Clock::now();
  double cpu = process_cpu_seconds();
  auto cpu_since = [&cpu] {
    const double now = process_cpu_seconds(), d = now - cpu;
    cpu = now;
    return d;
  };
  SceneDesc scene = load_unsubdivided(args);
  r.parse_seconds = seconds_since(t);
  r.parse_cpu_seconds = cpu_since();
  r.parse_peak_rss = phase_peak();

  t = Clock::now();
  apply_subdivision(scene);
  r.subdivision_seconds = seconds_since(t);
  r.subdivision_cpu_seconds = cpu_since();
  r.subdivision_peak_rss = phase_peak();

  t = Clock::now();
  RuleOverrides overrides;
  overrides.rules = args.rules;
  overrides.light_sampler = args.light_sampler;
  const SceneRules rules = resolve_rules(scene, overrides);
  WorldOptions wo;
  wo.accel = args.accel;
  wo.ellipsoid_pdf = ellipsoid_pdf(rules, overrides);
  wo.env_map_sampling = env_map_sampling(rules, overrides);
  wo.light_sampler = light_sampler_kind(rules, overrides);
  r.scene_desc_bytes = scene_desc_bytes(scene);  // measured before the world takes the arrays over
  const auto world = build_world_taking_meshes(scene, wo);
  const double build_seconds = seconds_since(t);
  r.build_cpu_seconds = cpu_since();
  const AccelStats as = world->accel->stats();
  r.accel = as.name;
  r.accel_build_seconds = as.build_seconds;
  r.world_build_seconds = std::max(0.0, build_seconds - as.build_seconds);
  r.build_peak_rss = phase_peak();
  r.meshes = world->stats.meshes;
  r.triangles = world->stats.triangles;
  r.world_geometry_bytes = world_geometry_bytes(world->geometry);
  for (const auto& n : world->normals) r.world_normals_bytes += vector_bytes(n);
  r.accel_bytes = as.bytes;

  if (!args.no_render) {
    if (scene.cameras.empty()) throw Error(args.scene, "", "scene has no camera (use --no-render)");
    const CameraDesc* cd = &scene.cameras.front();
    if (args.camera) {
      const auto it = std::find_if(scene.cameras.begin(), scene.cameras.end(),
                                   [&](const CameraDesc& c) { return c.id == *args.camera; });
      if (it == scene.cameras.end()) throw Error(args.scene, "", "no camera with id '" + *args.camera + "'");
      cd = &*it;
    }
    const Camera camera(*cd);
    const IntegratorSettings settings = camera_settings(*cd, scene, rules, overrides, world->features);
    RenderOptions ro;
    ro.seed = args.seed;
    ro.spp_total = std::max(1u, args.spp);
    ro.time_ray_queries = true;
    Film film(camera.width(), camera.height());
    cpu_since();
    const RenderStats rs = render_samples(*world, camera, settings, ro, 0, ro.spp_total, film);
    r.render_cpu_seconds = cpu_since();
    r.rendered = true;
    r.camera = cd->id;
    r.width = camera.width();
    r.height = camera.height();
    r.spp = ro.spp_total;
    r.render_seconds = rs.seconds;
    r.primary = ray_kind(rs.rays.primary, rs.seconds, rs.rays.primary_cycles);
    r.shadow = ray_kind(rs.rays.shadow, rs.seconds, rs.rays.shadow_cycles);
    r.indirect = ray_kind(rs.rays.indirect, rs.seconds, rs.rays.indirect_cycles);
    r.total = ray_kind(rs.rays.total(), rs.seconds, rs.rays.query_cycles());
    r.mrays_per_cpu_second = double(rs.rays.total()) / std::max(1e-9, r.render_cpu_seconds) / 1e6;
    // TSC cycles in queries include time the thread was descheduled, so they are compared with wall x threads,
    // which does too (the render's CPU time does not).
    const double thread_seconds = std::max(1e-9, rs.seconds * double(r.threads));
    r.ray_query_share = std::clamp(double(rs.rays.query_cycles()) / tsc_frequency() / thread_seconds, 0.0, 1.0);
    r.render_peak_rss = phase_peak();
    r.media = !world->media.empty();
    r.medium_segments = rs.rays.media.rays;
    r.medium_collisions = rs.rays.media.collisions;
    r.steps_per_segment = rs.rays.media.steps_per_ray();
    r.majorant_efficiency = rs.rays.media.majorant_efficiency();
  }
  r.total_seconds = seconds_since(t_start);
  return r;
}

std::string profile_json(const ProfileReport& r) {
  auto kind = [](const RayKindStats& k) {
    return nlohmann::json{{"count", k.count},
                          {"mrays_per_second", k.mrays_per_second},
                          {"query_mrays_per_thread_second", k.query_mrays_per_second}};
  };
  nlohmann::json j;
  j["scene"] = r.scene;
  j["subdivide"] = r.subdivide >= 0 ? nlohmann::json(r.subdivide) : nlohmann::json("scene");
  j["accel"] = r.accel;
  j["threads"] = r.threads;
  j["meshes"] = r.meshes;
  j["triangles"] = r.triangles;
  j["phases"] = {{"parse_seconds", r.parse_seconds},
                 {"subdivision_seconds", r.subdivision_seconds},
                 {"world_build_seconds", r.world_build_seconds},
                 {"accel_build_seconds", r.accel_build_seconds},
                 {"load_subdivision_build_seconds", r.load_subdivision_build_seconds()},
                 {"render_seconds", r.render_seconds},
                 {"total_seconds", r.total_seconds}};
  j["cpu_seconds"] = {{"parse", r.parse_cpu_seconds},
                      {"subdivision", r.subdivision_cpu_seconds},
                      {"world_and_accel_build", r.build_cpu_seconds},
                      {"render", r.render_cpu_seconds}};
  j["load_average"] = r.load_average;
  if (r.rendered) {
    j["render"] = {{"camera", r.camera}, {"width", r.width}, {"height", r.height}, {"spp", r.spp}};
    j["rays"] = {{"primary", kind(r.primary)}, {"shadow", kind(r.shadow)}, {"indirect", kind(r.indirect)},
                 {"total", kind(r.total)}, {"mrays_per_cpu_second", r.mrays_per_cpu_second}};
    j["time_share"] = {{"ray_queries", r.ray_query_share},
                       {"shading_and_sampling", 1.0 - r.ray_query_share},
                       {"note", "shading_and_sampling is the remainder of the render's thread time: shading, "
                                "BSDF and light sampling, camera rays, film and scheduling"}};
    if (r.media)
      j["media"] = {{"tracked_segments", r.medium_segments},
                    {"collisions", r.medium_collisions},
                    {"steps_per_segment", r.steps_per_segment},
                    {"majorant_efficiency", r.majorant_efficiency},
                    {"collisions_per_second", double(r.medium_collisions) / std::max(1e-9, r.render_seconds)}};
  }
  j["memory"] = {{"peak_rss_bytes", r.peak_rss},
                 {"baseline_rss_bytes", r.baseline_rss},
                 {"bytes_per_triangle", r.bytes_per_triangle()},
                 {"net_bytes_per_triangle", r.net_bytes_per_triangle()},
                 {"peak_source", r.peak_source},
                 {"per_phase_peaks", r.peak_reset_supported},
                 {"phase_peak_rss_bytes",
                  {{"parse", r.parse_peak_rss},
                   {"subdivision", r.subdivision_peak_rss},
                   {"build", r.build_peak_rss},
                   {"render", r.render_peak_rss}}},
                 {"scene_desc_bytes", r.scene_desc_bytes},
                 {"world_geometry_bytes", r.world_geometry_bytes},
                 {"world_normals_bytes", r.world_normals_bytes},
                 {"accel_bytes", r.accel_bytes}};
  return j.dump(2);
}

std::string profile_table(const ProfileReport& r) {
  std::string out;
  char line[256];
  auto add = [&](const char* fmt, auto... v) {
    std::snprintf(line, sizeof line, fmt, v...);
    out += line;
  };
  const double tri = double(std::max<size_t>(1, r.triangles));
  auto mib = [](size_t b) { return double(b) / kMiB; };
  add("kiln profile: %s\n", r.scene.c_str());
  add("  subdivide %s, accelerator %s, %d threads, %zu meshes, %zu triangles (machine load %.1f)\n",
      r.subdivide >= 0 ? std::to_string(r.subdivide).c_str() : "as in scene", r.accel.c_str(), r.threads, r.meshes,
      r.triangles, r.load_average);
  add("\n  %-26s %10s %10s\n", "phase", "seconds", "cpu s");
  add("  %-26s %10.3f %10.3f\n", "parse", r.parse_seconds, r.parse_cpu_seconds);
  add("  %-26s %10.3f %10.3f\n", "subdivision", r.subdivision_seconds, r.subdivision_cpu_seconds);
  add("  %-26s %10.3f %10s\n", "world build", r.world_build_seconds, "(below)");
  add("  %-26s %10.3f %10.3f   (cpu: world + accelerator)\n", "accelerator build", r.accel_build_seconds,
      r.build_cpu_seconds);
  add("  %-26s %10.3f %10.3f\n", "load+subdivision+build", r.load_subdivision_build_seconds(),
      r.parse_cpu_seconds + r.subdivision_cpu_seconds + r.build_cpu_seconds);
  if (r.rendered) {
    add("  %-26s %10.3f %10.3f   (camera %s, %dx%d, %u spp)\n", "render", r.render_seconds, r.render_cpu_seconds,
        r.camera.c_str(), r.width, r.height, r.spp);
    add("\n  %-26s %14s %10s %14s\n", "rays", "count", "Mrays/s", "query Mrays/s");
    for (const auto& [name, k] : {std::pair{"primary", r.primary}, std::pair{"shadow", r.shadow},
                                  std::pair{"indirect", r.indirect}, std::pair{"total", r.total}})
      add("  %-26s %14llu %10.2f %14.2f\n", name, (unsigned long long)k.count, k.mrays_per_second,
          k.query_mrays_per_second);
    add("  %-26s %14s %10.2f\n", "total per CPU second", "", r.mrays_per_cpu_second);
    add("  (query Mrays/s: rays per second of one thread's time inside accelerator queries)\n");
    add("\n  render thread time: %.0f%% ray queries, %.0f%% shading+sampling (remainder: shading, BSDF/light "
        "sampling, camera rays, film, scheduling)\n",
        100.0 * r.ray_query_share, 100.0 * (1.0 - r.ray_query_share));
    if (r.media)
      add("  media: %llu tracked segments, %.2f steps per segment, majorant efficiency %.2f, %.2f M collisions/s\n",
          (unsigned long long)r.medium_segments, r.steps_per_segment, r.majorant_efficiency,
          double(r.medium_collisions) / std::max(1e-9, r.render_seconds) / 1e6);
  }
  add("\n  memory: peak RSS %.1f MiB = %.0f B/triangle (%.0f B/triangle above the %.1f MiB baseline; %s)\n",
      mib(r.peak_rss), r.bytes_per_triangle(), r.net_bytes_per_triangle(), mib(r.baseline_rss), r.peak_source.c_str());
  add("  %-26s %10s %12s\n", r.peak_reset_supported ? "phase peak RSS" : "peak RSS so far", "MiB", "");
  add("  %-26s %10.1f\n", "parse", mib(r.parse_peak_rss));
  add("  %-26s %10.1f\n", "subdivision", mib(r.subdivision_peak_rss));
  add("  %-26s %10.1f\n", "world + accelerator build", mib(r.build_peak_rss));
  if (r.rendered) add("  %-26s %10.1f\n", "render", mib(r.render_peak_rss));
  add("  %-26s %10s %12s\n", "held data", "MiB", "B/triangle");
  for (const auto& [name, b] : {std::pair{"scene description (moved)", r.scene_desc_bytes},
                                std::pair{"world geometry", r.world_geometry_bytes},
                                std::pair{"smooth normals", r.world_normals_bytes},
                                std::pair{"accelerator", r.accel_bytes}})
    add("  %-26s %10.1f %12.1f\n", name, mib(b), double(b) / tri);
  add("  %-26s %10.3f\n", "total seconds", r.total_seconds);
  return out;
}

int cmd_profile(const ProfileArgs& args) {
  const ProfileReport r = run_profile(args);
  const std::string text = args.json ? profile_json(r) + "\n" : profile_table(r);
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  return 0;
}

}  // namespace kiln
