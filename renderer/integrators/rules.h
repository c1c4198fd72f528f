// The seam between Kiln's rules and the courses' (README, "Two rule sets"): which rule set renders a scene, and the
// integrator settings every camera gets from it. Every command-line override of the integrators is decided here; the
// defaults the rule sets start from are named once, in renderer/integrators/settings.h (k...Default...).
//
//   Kiln             Kiln's path tracer: MIS of NEE and BRDF sampling (power heuristic), unbiased roulette after
//                    kKilnRouletteMinDepth bounces, MaxRecursionDepth (else kKilnDefaultMaxDepth) bounces, exact light
//                    densities, jittered pixel samples.
//   CENG795 course   cameras without a renderer: the course ray tracer (MaxRecursionDepth, else
//                    kCourseDefaultRecursion; ShadowRayEpsilon offsets); PathTracing cameras: the course path tracer
//                    with the camera's RendererParams (its roulette, NEE at the last vertex, the Fresnel split);
//                    ellipsoid lights divided by their object-space cone pdf; 1 spp samples pixel centres.
//   CS171 course     the framework's iterative path tracer: NEE without MIS, no roulette, max_depth vertices gather
//                    direct light (spec §7), which is Kiln's path tracer with the nee strategy and max_depth bounces.
#pragma once
#include <optional>
#include <string>

#include "renderer/integrators/integrator.h"

namespace kiln {

// What the command line says about the integrators (kiln render; kiln profile and kiln info take the rule set only).
struct RuleOverrides {
  std::optional<std::string> rules;            // --rules kiln|course
  std::optional<std::string> strategy;         // --strategy: one of Kiln's path-tracing strategies (Kiln's rules)
  std::optional<bool> russian_roulette;        // --rr
  std::optional<int> max_depth;                // --max-depth
  std::optional<std::string> course_roulette;  // --course-roulette literal|expected
  bool physical_lights = false;                // --physical-lights: exact light densities under the course's rules
  std::optional<std::string> light_sampler;    // --light-sampler power|uniform|bvh (Kiln's rules)
  float clamp = 0.0f;                          // --clamp
};

const char* rules_name(SceneRules rules);

// The rule set for the scene; throws kiln::Error for an override the rule set cannot take.
SceneRules resolve_rules(const SceneDesc& scene, const RuleOverrides& overrides);

// The density ellipsoid lights sample with under the rule set (the world is built with it).
EllipsoidPdf ellipsoid_pdf(SceneRules rules, const RuleOverrides& overrides);

// How environment maps are sampled under the rule set: the CENG795 course's uniform hemisphere (pdf 1/2pi, its
// spec) or Kiln's luminance-proportional importance sampling (also the course's with --physical-lights).
EnvMapSampling env_map_sampling(SceneRules rules, const RuleOverrides& overrides);

// How next event estimation chooses lights under the rule set: the course rule sets keep the power-proportional
// selector their references were rendered with; Kiln's rules take --light-sampler, else (empty) the scene's default
// (lights/light_sampler.h).
std::optional<LightSamplerKind> light_sampler_kind(SceneRules rules, const RuleOverrides& overrides);

// The integrator and its settings for one camera. features: the world's feature mask.
IntegratorSettings camera_settings(const CameraDesc& camera, const SceneDesc& scene, SceneRules rules,
                                   const RuleOverrides& overrides, uint32_t features);

// Kiln's path tracer with settings s for a camera of the scene: its volumetric path tracer when the scene has media
// (a shape bounding one, or a camera inside one), so that scenes without media keep the surface path tracer's speed.
IntegratorSettings kiln_path_integrator(const PathSettings& s, const SceneDesc& scene, const CameraDesc& camera);

// Kiln's own path-tracing defaults for a scene (what every strategy study starts from).
PathSettings kiln_path_defaults(const SceneDesc& scene);

// A named strategy of Kiln's path tracer on top of base: uniform, cosine, brdf (direction sampling alone), nee, mis;
// a "+rr" suffix turns roulette on (else base's roulette stays). Throws kiln::Error naming `option` otherwise.
PathSettings kiln_strategy(const std::string& name, PathSettings base, const std::string& option);

}  // namespace kiln
