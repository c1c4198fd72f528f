// The integrators' settings: one struct per integrator, and IntegratorSettings, the variant that says which one
// renders a camera. Which one a camera gets, and with which values, is decided by the rule sets
// (renderer/integrators/rules.h) from the defaults below. A new integrator adds its settings to the variant and an
// `integrate` overload for them (renderer/integrators/integrator.h): trace() and describe() visit the variant, so a
// missing overload is a compile error, not a run-time one.
#pragma once
#include <cstdint>
#include <string>
#include <variant>

#include "renderer/world/features.h"

namespace kiln {

// The rule sets' defaults (renderer/integrators/rules.h): what a camera gets when neither its scene nor the command
// line says otherwise. The settings below start from them; nothing else repeats them.
inline constexpr int kKilnDefaultMaxDepth = 8;   // Kiln's path tracer (and the CS171 rules'): bounces
inline constexpr int kKilnRouletteMinDepth = 3;  // Kiln's roulette starts after this many bounces
inline constexpr int kCourseDefaultPathDepth = 8;  // the course path tracer without MaxRecursionDepth and roulette
inline constexpr int kCourseDefaultRecursion = 5;  // the course ray tracer without MaxRecursionDepth
inline constexpr float kCourseDefaultShadowRayEpsilon = 1e-3f;  // the course framework parser's ShadowRayEpsilon
// Whether the course renderer culls back faces for camera rays when a scene does not say (README, "Course
// conventions").
inline constexpr bool kCourseCullsCameraBackfaces = false;

enum class DirectionSampling { Uniform, Cosine, Brdf };

// Kiln's path tracer (renderer/integrators/path_tracer.cpp): direction sampling, next event estimation, MIS with the
// power heuristic, unbiased throughput roulette and a depth cap.
struct PathSettings {
  DirectionSampling directions = DirectionSampling::Brdf;
  bool nee = true;
  bool mis = true;              // weight NEE and direction sampling with the power heuristic (needs nee)
  bool russian_roulette = true;
  int max_depth = kKilnDefaultMaxDepth;      // bounces after the camera ray; < 0: unlimited (only with roulette)
  int rr_min_depth = kKilnRouletteMinDepth;  // roulette starts after this many bounces
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
  // MaxRecursionDepth: the vertex at this depth still samples lights; < 0: unlimited (roulette)
  int max_depth = kCourseDefaultPathDepth;
  bool cull_camera_backfaces = kCourseCullsCameraBackfaces;  // BackfaceCulling (README, "Course conventions")
};

// The CENG795 course's direct-lighting (Whitted-style) ray tracer (renderer/integrators/course_ray_tracer.cpp).
struct CourseRaySettings {
  int max_depth = kCourseDefaultRecursion;  // recursion depth of mirror / dielectric / conductor rays
  // ShadowRayEpsilon: secondary rays start this far along the normal
  float ray_epsilon = kCourseDefaultShadowRayEpsilon;
  bool cull_camera_backfaces = kCourseCullsCameraBackfaces;  // BackfaceCulling (README, "Course conventions")
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

}  // namespace kiln
