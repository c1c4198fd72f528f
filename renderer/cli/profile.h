// `kiln profile SCENE|MESH`: where the time and the memory go for one scene. Phases are timed separately
// (parse, Loop subdivision, world build, accelerator build, render of one camera), in wall-clock and process CPU
// seconds (CPU time stays meaningful on a machine shared with other jobs). Rays are counted by kind; the render's
// thread time (wall x threads) is split into ray queries (TSC cycles inside accelerator queries) and the remainder
// (shading + light/BSDF sampling + camera rays + film + scheduling; the integrators do not time these apart).
// Memory is the process's peak resident set (VmHWM; reset per phase through /proc/self/clear_refs when the kernel
// allows, so tools that read this process's peak afterwards see only the last phase; else ru_maxrss) plus the
// sizes of the big arrays (scene description, world geometry, normals, accelerator). No image is written.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "renderer/accel/accelerator.h"

namespace kiln {

struct ProfileArgs {
  std::string scene;
  int subdivide = -1;  // < 0: each mesh's own setting
  AccelKind accel = AccelKind::Embree;
  uint32_t spp = 4;    // the timed render's samples per pixel
  std::optional<std::string> camera;
  int threads = 0;     // 0: all cores
  uint64_t seed = 0;
  bool no_render = false;
  bool json = false;
  std::optional<std::string> rules;  // kiln | course; default: the scene's own
  std::optional<std::string> light_sampler;  // power | uniform | bvh (Kiln's rules); default: the scene's
};

struct RayKindStats {
  uint64_t count = 0;
  double mrays_per_second = 0;  // per wall-clock second of the render phase
  // Per second of one thread's time inside accelerator queries of this kind: with --spp 1 --threads 1 on
  // scenes/killeroo_path.xml these are the very rays `kiln_bench --benchmark_filter=AccelReplay` traces raw (how much
  // Kiln's shading and cache traffic cost the accelerator).
  double query_mrays_per_second = 0;
};

struct ProfileReport {
  std::string scene;
  int subdivide = -1;
  std::string accel;
  int threads = 0;
  size_t meshes = 0, triangles = 0;  // as rendered (instanced triangles once per instance)
  // Phases, wall-clock seconds.
  double parse_seconds = 0, subdivision_seconds = 0, world_build_seconds = 0, accel_build_seconds = 0;
  double render_seconds = 0, total_seconds = 0;
  double load_subdivision_build_seconds() const {
    return parse_seconds + subdivision_seconds + world_build_seconds + accel_build_seconds;
  }
  // Process CPU seconds (all threads) per phase: robust to other processes on a shared machine, where wall
  // times stretch. The accelerator is built inside the world build, so their CPU time is one figure.
  double parse_cpu_seconds = 0, subdivision_cpu_seconds = 0, build_cpu_seconds = 0, render_cpu_seconds = 0;
  double load_average = 0;  // 1-minute load average of the machine when the profile started (/proc/loadavg)
  // Render.
  bool rendered = false;
  std::string camera;
  int width = 0, height = 0;
  uint32_t spp = 0;
  RayKindStats primary, shadow, indirect, total;
  double mrays_per_cpu_second = 0;  // total rays per second of render CPU time (per core, robust to contention)
  double ray_query_share = 0;  // of the render's thread time (render_seconds x threads)
  // Participating media (scenes with media only): tracking through them.
  bool media = false;
  uint64_t medium_segments = 0, medium_collisions = 0;
  double steps_per_segment = 0, majorant_efficiency = 0;
  // Memory (bytes). Peaks are per phase when peak_reset_supported, else the process peak so far.
  size_t baseline_rss = 0, peak_rss = 0;
  size_t parse_peak_rss = 0, subdivision_peak_rss = 0, build_peak_rss = 0, render_peak_rss = 0;
  bool peak_reset_supported = false;
  std::string peak_source;  // "VmHWM" or "ru_maxrss"
  size_t scene_desc_bytes = 0;       // MeshDesc positions/indices/normals/uvs as loaded (then moved into the world)
  size_t world_geometry_bytes = 0;   // WorldGeometry meshes and prototypes
  size_t world_normals_bytes = 0;    // World::normals
  size_t accel_bytes = 0;            // as the accelerator reports it
  double bytes_per_triangle() const { return triangles ? double(peak_rss) / double(triangles) : 0.0; }
  double net_bytes_per_triangle() const {
    return triangles ? double(peak_rss > baseline_rss ? peak_rss - baseline_rss : 0) / double(triangles) : 0.0;
  }
};

// Runs the phases and measures them; throws kiln::Error on bad input.
ProfileReport run_profile(const ProfileArgs& args);
std::string profile_json(const ProfileReport& report);   // pretty-printed JSON object
std::string profile_table(const ProfileReport& report);  // human-readable table
// run_profile, then prints the table (or the JSON with args.json) to stdout; returns the exit code.
int cmd_profile(const ProfileArgs& args);

}  // namespace kiln
