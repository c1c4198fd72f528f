#include "renderer/integrators/rules.h"

#include <string_view>

#include "core/error.h"
#include "renderer/world/world_media.h"

namespace kiln {
namespace {

inline constexpr char kRrSuffix[] = "+rr";
inline constexpr char kHeroSuffix[] = "+hero";

bool is_course(SceneRules r) { return r != SceneRules::Kiln; }

CourseRoulette course_roulette_mode(const RuleOverrides& o) {
  if (!o.course_roulette || *o.course_roulette == "literal") return CourseRoulette::Literal;
  if (*o.course_roulette == "expected") return CourseRoulette::Expected;
  throw Error("--course-roulette", "", "unknown mode '" + *o.course_roulette + "' (literal, expected)");
}

IntegratorSettings kiln_camera(const CameraDesc& camera, const SceneDesc& scene, const RuleOverrides& o) {
  PathSettings s = kiln_path_defaults(scene);
  if (o.strategy) s = kiln_strategy(*o.strategy, s, "--strategy");
  if (o.russian_roulette) s.russian_roulette = *o.russian_roulette;
  if (o.max_depth) s.max_depth = *o.max_depth;
  if (s.max_depth < 0 && !s.russian_roulette) throw Error("--max-depth", "", "unlimited depth needs --rr true");
  return kiln_path_integrator(s, scene, camera);
}

IntegratorSettings ceng795_camera(const CameraDesc& camera, const SceneDesc& scene, const RuleOverrides& o) {
  if (camera.renderer == RendererKind::RayTracing) {
    CourseRaySettings s;
    s.max_depth = o.max_depth.value_or(scene.max_recursion_depth.value_or(kCourseDefaultRecursion));
    s.ray_epsilon = scene.shadow_ray_epsilon.value_or(kCourseDefaultShadowRayEpsilon);
    s.cull_camera_backfaces = scene.backface_culling.value_or(kCourseCullsCameraBackfaces);
    return s;
  }
  CoursePathSettings s;
  s.importance_sampling = camera.pt.importance_sampling;
  s.nee = camera.pt.next_event_estimation;
  s.cull_camera_backfaces = scene.backface_culling.value_or(kCourseCullsCameraBackfaces);
  const bool roulette = o.russian_roulette.value_or(camera.pt.russian_roulette);
  s.roulette = roulette ? course_roulette_mode(o) : CourseRoulette::Off;
  // The course's roulette replaces its depth cap.
  s.max_depth = o.max_depth.value_or(roulette ? -1 : scene.max_recursion_depth.value_or(kCourseDefaultPathDepth));
  if (s.max_depth < 0 && !roulette) throw Error("--max-depth", "", "unlimited depth needs --rr true");
  return s;
}

IntegratorSettings cs171_camera(const CameraDesc& camera, const SceneDesc& scene, const RuleOverrides& o) {
  PathSettings s;
  s.directions = DirectionSampling::Brdf;
  s.nee = true;
  s.mis = false;
  s.russian_roulette = o.russian_roulette.value_or(false);
  s.max_depth = o.max_depth.value_or(scene.max_recursion_depth.value_or(kKilnDefaultMaxDepth));
  if (s.max_depth < 0 && !s.russian_roulette) throw Error("--max-depth", "", "unlimited depth needs --rr true");
  return kiln_path_integrator(s, scene, camera);
}

}  // namespace

const char* rules_name(SceneRules rules) {
  switch (rules) {
    case SceneRules::Kiln: return "Kiln's rules";
    case SceneRules::Ceng795Course: return "CENG795 course rules";
    case SceneRules::Cs171Course: return "CS171 course rules";
  }
  return "?";
}

SceneRules resolve_rules(const SceneDesc& scene, const RuleOverrides& o) {
  SceneRules rules = scene.rules;
  if (o.rules) {
    if (*o.rules == "kiln") {
      rules = SceneRules::Kiln;
    } else if (*o.rules == "course") {
      if (!is_course(scene.rules))
        throw Error("--rules", "", "'course': " + scene.source_path + " is not a course scene; it has Kiln's rules only");
      if (o.strategy)
        throw Error("--strategy", "", "picks one of Kiln's path-tracing strategies and cannot be combined with --rules course");
    } else {
      throw Error("--rules", "", "unknown rule set '" + *o.rules + "' (kiln, course)");
    }
  }
  // A strategy is one of Kiln's own: it renders with Kiln's rules.
  if (o.strategy) {
    kiln_strategy(*o.strategy, PathSettings{}, "--strategy");  // a bad name fails before the world is built
    rules = SceneRules::Kiln;
  }
  if (o.course_roulette && rules != SceneRules::Ceng795Course)
    throw Error("--course-roulette", "", "applies to the CENG795 course's rules only");
  if (o.course_roulette) course_roulette_mode(o);  // validate the mode even where no camera uses it
  if (o.light_sampler) {
    if (!parse_light_sampler(*o.light_sampler))
      throw Error("--light-sampler", "", "unknown light sampler '" + *o.light_sampler + "' (power, uniform, bvh)");
    if (rules != SceneRules::Kiln)
      throw Error("--light-sampler", "", "applies to Kiln's rules only: the " + std::string(rules_name(rules)) +
                                             " keep their own light selection (add --rules kiln)");
  }
  return rules;
}

EllipsoidPdf ellipsoid_pdf(SceneRules rules, const RuleOverrides& o) {
  return rules == SceneRules::Ceng795Course && !o.physical_lights ? EllipsoidPdf::CourseObjectSpace
                                                                  : EllipsoidPdf::Exact;
}

EnvMapSampling env_map_sampling(SceneRules rules, const RuleOverrides& o) {
  return rules == SceneRules::Ceng795Course && !o.physical_lights ? EnvMapSampling::UniformHemisphere
                                                                  : EnvMapSampling::ImportanceSampled;
}

std::optional<LightSamplerKind> light_sampler_kind(SceneRules rules, const RuleOverrides& o) {
  if (rules != SceneRules::Kiln) return LightSamplerKind::Power;
  return o.light_sampler ? parse_light_sampler(*o.light_sampler) : std::nullopt;
}

IntegratorSettings camera_settings(const CameraDesc& camera, const SceneDesc& scene, SceneRules rules,
                                   const RuleOverrides& o, uint32_t features) {
  IntegratorSettings s;
  switch (rules) {
    case SceneRules::Kiln: s = kiln_camera(camera, scene, o); break;
    case SceneRules::Ceng795Course:
      s = ceng795_camera(camera, scene, o);
      s.centre_single_sample = true;
      break;
    case SceneRules::Cs171Course: s = cs171_camera(camera, scene, o); break;
  }
  s.features = features;
  s.clamp = o.clamp;
  return s;
}

IntegratorSettings kiln_path_integrator(const PathSettings& s, const SceneDesc& scene, const CameraDesc& camera) {
  if (!scene_uses_media(scene)) return s;
  return VolPathSettings{s, camera.medium};
}

PathSettings kiln_path_defaults(const SceneDesc& scene) {
  PathSettings s;
  s.max_depth = scene.max_recursion_depth.value_or(kKilnDefaultMaxDepth);
  return s;
}

PathSettings kiln_strategy(const std::string& name, PathSettings base, const std::string& option) {
  std::string core = name;
  const auto strip = [&](std::string_view suffix) {
    const size_t n = suffix.size();
    if (core.size() <= n || core.compare(core.size() - n, n, suffix) != 0) return false;
    core.resize(core.size() - n);
    return true;
  };
  // Each suffix at most once, in either order ("nee+rr+hero", "nee+hero+rr"; not "nee+rr+rr").
  bool rr = false, hero = false;
  for (bool more = true; more;) {
    more = false;
    if (!rr && strip(kRrSuffix)) more = rr = true;
    if (!hero && strip(kHeroSuffix)) more = hero = true;
  }
  if (rr) base.russian_roulette = true;
  if (hero) base.channel_mis = false;
  base.nee = base.mis = false;
  if (core == "uniform") {
    base.directions = DirectionSampling::Uniform;
  } else if (core == "cosine") {
    base.directions = DirectionSampling::Cosine;
  } else if (core == "brdf") {
    base.directions = DirectionSampling::Brdf;
  } else if (core == "nee") {
    base.directions = DirectionSampling::Brdf;
    base.nee = true;
  } else if (core == "mis") {
    base.directions = DirectionSampling::Brdf;
    base.nee = base.mis = true;
  } else {
    throw Error(option, "", "unknown strategy '" + name +
                                "' (uniform, cosine, brdf, nee, mis; append +rr for Russian roulette, e.g. nee+rr, and +hero "
                                "to weight media by the tracked channel alone)");
  }
  return base;
}

}  // namespace kiln
