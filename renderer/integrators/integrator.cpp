#include "renderer/integrators/integrator.h"

namespace kiln {
namespace {

const char* name_of(DirectionSampling d) {
  switch (d) {
    case DirectionSampling::Uniform: return "uniform";
    case DirectionSampling::Cosine: return "cosine";
    case DirectionSampling::Brdf: return "brdf";
  }
  return "?";
}

std::string depth_of(int max_depth) { return max_depth < 0 ? "unlimited" : std::to_string(max_depth); }

std::string describe_strategy(const PathSettings& s) {
  return std::string(name_of(s.directions)) + (s.nee ? (s.mis ? "+nee+mis" : "+nee") : "") +
         (s.russian_roulette ? "+rr" : "") + ", max depth " + depth_of(s.max_depth);
}

std::string describe_method(const PathSettings& s) { return "Kiln path tracer: " + describe_strategy(s); }

std::string describe_method(const VolPathSettings& s) {
  std::string d = "Kiln volumetric path tracer: " + describe_strategy(s.path);
  if (!s.path.channel_mis) d += ", one channel per path (no channel MIS)";
  if (s.camera_medium >= 0) d += ", camera in medium " + std::to_string(s.camera_medium);
  return d;
}

std::string describe_method(const CoursePathSettings& s) {
  const char* roulette = s.roulette == CourseRoulette::Literal    ? "+course-rr(literal)"
                         : s.roulette == CourseRoulette::Expected ? "+course-rr(expected)"
                                                                  : "";
  return std::string("course path tracer: ") + (s.importance_sampling ? "brdf" : "uniform") + (s.nee ? "+nee" : "") +
         roulette + "+fresnel-split" + (s.cull_camera_backfaces ? "+backface-culling" : "") + ", max depth " +
         depth_of(s.max_depth);
}

std::string describe_method(const CourseRaySettings& s) {
  return std::string("course ray tracer") + (s.cull_camera_backfaces ? " (backface culling)" : "") + ", depth " +
         std::to_string(s.max_depth);
}

}  // namespace

std::string IntegratorSettings::describe() const {
  std::string d = std::visit([](const auto& m) { return describe_method(m); }, method);
  if (clamp > 0.0f) d += ", clamp " + std::to_string(clamp);
  return d;
}

Rgb trace(const RenderContext& ctx, const Ray& ray, Vec2f film, Sampler& sampler, RayCounters& c,
          VisibleSurface* visible) {
  const IntegratorSettings& s = ctx.settings;
  Rgb L =
      std::visit([&](const auto& method) { return integrate(ctx, method, ray, film, sampler, c, visible); }, s.method);
  if (s.clamp > 0.0f) {
    const float mx = L.max_component();
    if (mx > s.clamp) L *= s.clamp / mx;
  }
  return L;
}

}  // namespace kiln
