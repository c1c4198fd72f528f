// The integrators and their settings. Kiln's own path tracer is what every scene gets under Kiln's rules; the
// course path tracer and the course ray tracer reproduce the CENG795 reference renderer. Which one renders a camera,
// and with which settings, is decided in one place: renderer/integrators/rules.h. Every integrator is a pure function of
// (world, camera ray, per-sample sampler), so output is independent of threads and tile order.
#pragma once
#include <cstdint>
#include <string>
#include <variant>

#include "core/sampler.h"
#include "media/tracking.h"
#include "renderer/world/world.h"

namespace kiln {

enum class DirectionSampling { Uniform, Cosine, Brdf };

// Kiln's path tracer (renderer/integrators/path_tracer.cpp): direction sampling, next event estimation, MIS with the power
// heuristic, unbiased throughput roulette and a depth cap.
struct PathSettings {
  DirectionSampling directions = DirectionSampling::Brdf;
  bool nee = true;
  bool mis = true;              // weight NEE and direction sampling with the power heuristic (needs nee)
  bool russian_roulette = true;
  int max_depth = 8;            // bounces after the camera ray; < 0: unlimited (only with roulette)
  int rr_min_depth = 3;         // roulette starts after this many bounces
  // Participating media only (the volumetric path tracer): distances are sampled on one channel per path, and
  // the three channels' densities are combined by the balance heuristic; false weights by the sampled channel's
  // density alone (unbiased too, but noisy where extinction differs across channels).
  bool channel_mis = true;
};

// Kiln's volumetric path tracer (renderer/integrators/vol_path_tracer.cpp): Kiln's path tracer through participating
// media, with the same strategies; every camera of a scene with media gets it (renderer/integrators/rules.h).
struct VolPathSettings {
  PathSettings path;
  int camera_medium = -1;  // index into World::media of the medium camera rays start in; -1: vacuum
};

// How the course's RussianRoulette is rendered (README, "Course conventions"). Literal replays its coin flips (its
// survivors' weights grow like (pi/kd)^(k(k+1)/2): unbounded variance); Expected applies their expectation, the
// 2 - p weight of the direct light at each vertex, and ends paths with Kiln's unbiased roulette (finite variance).
enum class CourseRoulette { Off, Expected, Literal };

// The CENG795 course's path tracer (renderer/integrators/course_path_tracer.cpp): its RendererParams and its rules.
struct CoursePathSettings {
  bool importance_sampling = false;  // BRDF sampling; otherwise uniform hemisphere directions
  bool nee = false;
  CourseRoulette roulette = CourseRoulette::Off;
  int max_depth = 8;  // MaxRecursionDepth: the vertex at this depth still samples lights; < 0: unlimited (roulette)
  bool cull_camera_backfaces = false;  // BackfaceCulling (README, "Course conventions")
};

// The CENG795 course's direct-lighting (Whitted-style) ray tracer (renderer/integrators/course_ray_tracer.cpp).
struct CourseRaySettings {
  int max_depth = 5;          // recursion depth of mirror / dielectric / conductor rays
  float ray_epsilon = 1e-3f;  // ShadowRayEpsilon: secondary rays start this far along the normal
  bool cull_camera_backfaces = false;  // BackfaceCulling (README, "Course conventions")
};

struct IntegratorSettings {
  std::variant<PathSettings, VolPathSettings, CoursePathSettings, CourseRaySettings> method;
  uint32_t features = kFeatureAll;  // the scene's feature mask: code paths for absent features are skipped
  float clamp = 0.0f;               // firefly clamp on each sample's radiance; 0 = off
  bool centre_single_sample = false;  // a 1-spp render samples pixel centres (the course's convention)

  IntegratorSettings() = default;
  IntegratorSettings(PathSettings s) : method(s) {}  // NOLINT: every integrator's settings are settings
  IntegratorSettings(VolPathSettings s) : method(s) {}  // NOLINT
  IntegratorSettings(CoursePathSettings s) : method(s) {}  // NOLINT
  IntegratorSettings(CourseRaySettings s) : method(s) {}  // NOLINT
  std::string describe() const;
};

// Per-thread counters, merged per tile (no atomics on the hot path).
struct RayCounters {
  uint64_t primary = 0, shadow = 0, indirect = 0;
  // TSC cycles spent inside accelerator queries, by ray kind (the query rate of each kind inside a render).
  uint64_t primary_cycles = 0, shadow_cycles = 0, indirect_cycles = 0;
  uint64_t nan_samples = 0;
  TrackingCounters media;  // the volumetric path tracer's tracking through media
  void add(const RayCounters& o) {
    primary += o.primary;
    shadow += o.shadow;
    indirect += o.indirect;
    primary_cycles += o.primary_cycles;
    shadow_cycles += o.shadow_cycles;
    indirect_cycles += o.indirect_cycles;
    nan_samples += o.nan_samples;
    media.add(o.media);
  }
  uint64_t total() const { return primary + shadow + indirect; }
  uint64_t query_cycles() const { return primary_cycles + shadow_cycles + indirect_cycles; }
};

// Sampler dimensions (core/sampler.h): the pixel position and lens come first, then the integrator's requests
// (renderer/integrators/path_vertex.h lays out the path tracers' per-vertex requests).
inline constexpr uint32_t kPixelDimension = 0;
inline constexpr uint32_t kLensDimension = 1;
inline constexpr uint32_t kFirstPathDimension = 2;
// The shutter time of a camera sample (motion blur), one per path: a dedicated stream (Sampler::dedicated_1d).
inline constexpr uint32_t kTimeStream = 0x74696d65u;  // "time"

// Radiance along a camera ray (the sampler is positioned at kFirstPathDimension). film: the ray's pixel on the
// image, its centre in [0, 1]^2 (x to the right, y down): where a camera ray that misses looks up the background
// texture (renderer/integrators/path_vertex.h, camera_background).
Rgb trace_path(const World& world, const PathSettings& s, uint32_t features, const Ray& ray, Vec2f film,
               Sampler& sampler, RayCounters& c);
Rgb trace_vol_path(const World& world, const VolPathSettings& s, uint32_t features, const Ray& ray, Vec2f film,
                   Sampler& sampler, RayCounters& c);
Rgb trace_course_path(const World& world, const CoursePathSettings& s, uint32_t features, const Ray& ray, Vec2f film,
                      Sampler& sampler, RayCounters& c);
Rgb trace_course_rays(const World& world, const CourseRaySettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
                      RayCounters& c);

// The integrator the settings name.
Rgb trace(const World& world, const IntegratorSettings& s, const Ray& ray, Vec2f film, Sampler& sampler,
          RayCounters& c);

// The film position of pixel (x, y) (y = 0 the top row) of a width x height image: its centre, (x + 1/2) / width,
// (y + 1/2) / height. The CENG795 spec (§1, BackgroundTexture) maps the background image to the image plane with
// "u = x/width, v = y/height"; x, y are read as the pixel's centre, so an image of the output's size shows texel
// (x, y) at pixel (x, y) whatever the rounding, and v grows downwards like the image's rows (the spec's pixel j and
// OpenImageIO's t both count from the top). One position per pixel, not per sample: the background is not blurred
// by the pixel filter and every sample of a pixel sees the same texel.
inline Vec2f pixel_film_position(int x, int y, int width, int height) {
  return {(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)};
}

}  // namespace kiln
