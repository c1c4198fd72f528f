// Point, spot, directional and square area lights inside the renderer, without the course data: a Lambertian
// plane of albedo a seen through a narrow camera has radiance a/pi * E, with E the irradiance at the point it sees,
// known in closed form for each light. Checked under Kiln's path tracer (NEE + MIS) and the course's ray tracer.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "renderer/test_scenes.h"

namespace kiln::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kAlbedo = 0.5f;
constexpr uint32_t kSamples = 20000;
// Delta lights have no Monte Carlo noise: what is left is float rounding and the pixel footprint's irradiance
// curvature.
constexpr double kDeltaRelTol = 2e-4;
constexpr double kMaxZ = 5.0;

struct LightCase {
  const char* name;
  std::function<void(SceneDesc&)> add;
  double irradiance;
  bool delta;
};

std::vector<LightCase> light_cases() {
  std::vector<LightCase> out;
  {  // Point light: I cos / d^2.
    const Vec3f p{0.3f, 2.0f, -0.4f};
    const double d2 = dot(p, p);
    out.push_back({"point", [p](SceneDesc& s) { s.point_lights.push_back({p, Rgb(3.0f)}); },
                   3.0 * (2.0 / std::sqrt(d2)) / d2, true});
  }
  {  // Spot light (full cone angles: coverage 60, falloff 20) with the origin 15 degrees off its axis:
     // I s^4, s = (cos 15 - cos 30) / (cos 10 - cos 30); then I' cos / d^2.
    const Vec3f p{0.0f, 2.0f, 0.0f};
    const double off = 15.0 * kPi / 180.0;
    const Vec3f axis{float(std::sin(off)), -float(std::cos(off)), 0.0f};  // 15 degrees off the way down
    const double s = (std::cos(off) - std::cos(kPi / 6)) / (std::cos(kPi / 18) - std::cos(kPi / 6));
    out.push_back({"spot",
                   [p, axis](SceneDesc& sc) { sc.spot_lights.push_back({p, axis, Rgb(4.0f), 60.0f, 20.0f}); },
                   4.0 * std::pow(s, 4.0) / 4.0, true});
  }
  {  // Directional light: E = radiance * cos.
    const Vec3f dir = normalize(Vec3f{1.0f, -2.0f, 0.5f});
    out.push_back({"directional", [dir](SceneDesc& s) { s.directional_lights.push_back({dir, Rgb(1.5f)}); },
                   1.5 * double(-dir.y), true});
  }
  {  // Square area light of side 1 at height 1.5, centred above the origin, facing down: four corner rectangles.
    out.push_back({"square area",
                   [](SceneDesc& s) {
                     AreaLightDesc a;
                     a.position = {0.0f, 1.5f, 0.0f};
                     a.normal = {0.0f, -1.0f, 0.0f};
                     a.size = 1.0f;
                     a.radiance = Rgb(2.0f);
                     s.area_lights.push_back(a);
                   },
                   4.0 * corner_rectangle_irradiance(2.0, 0.5, 0.5, 1.5), false});
  }
  return out;
}

// Why: each light's emission, falloff and sampling pdf reach the pixel as the closed form says, in both integrators.
TEST(LightIrradiance, LambertianPlaneMatchesTheClosedForm) {
  PathSettings kiln;
  kiln.max_depth = 2;
  kiln.russian_roulette = false;
  CourseRaySettings course;
  for (const LightCase& c : light_cases()) {
    SceneDesc s = lit_floor_scene(kAlbedo);
    c.add(s);
    const auto w = build_world(s, {});
    const double want = kAlbedo / kPi * c.irradiance;
    for (const auto& [integrator, settings] :
         {std::pair<const char*, IntegratorSettings>{"kiln", kiln}, {"course ray tracer", course}}) {
      const Estimate e = estimate_mean(*w, settings, s.cameras[0], kSamples);
      const double tol = c.delta ? kDeltaRelTol * want : kMaxZ * e.stderr_;
      EXPECT_NEAR(e.mean, want, tol) << c.name << ", " << integrator << ": " << e.mean << " +- " << e.stderr_;
      std::printf("%-12s %-18s %.6f (closed form %.6f, %+.2f se)\n", c.name, integrator, e.mean, want,
                  e.stderr_ > 0 ? (e.mean - want) / e.stderr_ : 0.0);
      if (!c.delta) {
        EXPECT_GT(e.stderr_, 0.0);
      }
    }
  }
}

}  // namespace
}  // namespace kiln::test
