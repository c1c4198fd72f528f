#include "renderer/integrator.h"

namespace kiln {

// Kiln's own path-tracing default: MIS with roulette after a minimum depth.
inline constexpr int kDefaultMaxDepth = 8;
// The course ray tracer's recursion depth when a scene does not give MaxRecursionDepth.
inline constexpr int kDefaultCourseRecursion = 5;
// The course framework's ShadowRayEpsilon when a scene does not give one (its parser's default).
inline constexpr float kDefaultCourseShadowRayEpsilon = 1e-3f;

IntegratorSettings settings_for_camera(const CameraDesc& camera, const SceneDesc& scene) {
  IntegratorSettings s;
  s.kind = camera.renderer;
  if (camera.renderer == RendererKind::RayTracing) {
    s.max_depth = scene.max_recursion_depth.value_or(kDefaultCourseRecursion);
    if (scene.format == "ceng795-xml")
      s.course_ray_epsilon = scene.shadow_ray_epsilon.value_or(kDefaultCourseShadowRayEpsilon);
    return s;
  }
  if (camera.renderer_explicit && (scene.format == "ceng795-xml" || scene.format == "cs171-json")) {
    // The course's path-tracing rules (README, "Course path-tracing semantics").
    s.directions = camera.pt.importance_sampling ? DirectionSampling::Brdf : DirectionSampling::Uniform;
    s.nee = camera.pt.next_event_estimation;
    s.mis = false;
    s.russian_roulette = camera.pt.russian_roulette;
    s.course_roulette = camera.pt.russian_roulette ? CourseRoulette::Literal : CourseRoulette::Off;
    s.nee_at_last_vertex = true;
    s.split_delta = true;
    s.max_depth = camera.pt.russian_roulette ? -1 : scene.max_recursion_depth.value_or(kDefaultMaxDepth);
    return s;
  }
  // Kiln default: MIS, roulette after a minimum depth, explicit depth cap.
  s.directions = DirectionSampling::Brdf;
  s.nee = s.mis = s.russian_roulette = true;
  s.max_depth = scene.max_recursion_depth.value_or(kDefaultMaxDepth);
  return s;
}

std::string IntegratorSettings::describe() const {
  if (kind == RendererKind::RayTracing) return "direct lighting (course ray tracer), depth " + std::to_string(max_depth);
  std::string d = directions == DirectionSampling::Uniform ? "uniform"
                  : directions == DirectionSampling::Cosine ? "cosine"
                                                            : "brdf";
  std::string s = "path tracing: " + d + (nee ? (mis ? "+nee+mis" : "+nee") : "") +
                  (russian_roulette ? "+rr" : "") + (split_delta ? "+fresnel-split" : "") +
                  (course_roulette == CourseRoulette::Expected  ? "+course-rr-weights"
                   : course_roulette == CourseRoulette::Literal ? "+course-rr(literal)"
                                                                : "");
  s += ", max depth " + (max_depth < 0 ? std::string("unlimited") : std::to_string(max_depth));
  return s;
}

}  // namespace kiln
