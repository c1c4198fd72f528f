// White furnace: inside a closed Lambertian box that emits Le everywhere, radiance is Le * sum_k a^k. Every
// strategy (uniform, cosine, BRDF, NEE, MIS; with and without roulette) must reach it within statistical error:
// this catches any pdf, MIS weight or roulette compensation that is off.
#include <gtest/gtest.h>

#include "renderer/render_util.h"

namespace kiln::test {
namespace {

struct FurnaceCase {
  const char* name;
  DirectionSampling dirs;
  bool nee, mis, rr;
  int max_depth;
};

PathSettings settings_of(const FurnaceCase& c) {
  PathSettings s;
  s.directions = c.dirs;
  s.nee = c.nee;
  s.mis = c.mis;
  s.russian_roulette = c.rr;
  // Roulette from the first bounce on for the unbounded cases (the harshest test of the compensation).
  s.rr_min_depth = c.max_depth < 0 ? 0 : 3;
  s.max_depth = c.max_depth;
  return s;
}

double expected(double a, double le, int depth) {
  if (depth < 0) return le / (1.0 - a);
  double sum = 0, ak = 1;
  for (int k = 0; k <= depth; ++k, ak *= a) sum += ak;
  return le * sum;
}

class Furnace : public ::testing::TestWithParam<FurnaceCase> {};

TEST_P(Furnace, MatchesAnalyticRadiance) {
  const FurnaceCase& fc = GetParam();
  for (const float albedo : {0.5f, 0.8f}) {
    const SceneDesc scene = furnace_box(albedo, Rgb(1.0f));
    const auto world = build_world(scene, {});
    const Estimate e = estimate_mean(*world, settings_of(fc), scene.cameras[0], 200000);
    const double want = expected(albedo, 1.0, fc.max_depth);
    EXPECT_NEAR(e.mean, want, 4.5 * e.stderr_ + 1e-4 * want)
        << fc.name << " albedo " << albedo << ": mean " << e.mean << " +- " << e.stderr_ << ", expected " << want;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Strategies, Furnace,
    ::testing::Values(FurnaceCase{"uniform_d5", DirectionSampling::Uniform, false, false, false, 5},
                      FurnaceCase{"cosine_d5", DirectionSampling::Cosine, false, false, false, 5},
                      FurnaceCase{"brdf_d5", DirectionSampling::Brdf, false, false, false, 5},
                      FurnaceCase{"nee_d5", DirectionSampling::Brdf, true, false, false, 5},
                      FurnaceCase{"nee_uniform_d5", DirectionSampling::Uniform, true, false, false, 5},
                      FurnaceCase{"mis_d5", DirectionSampling::Brdf, true, true, false, 5},
                      FurnaceCase{"mis_uniform_d5", DirectionSampling::Uniform, true, true, false, 5},
                      FurnaceCase{"mis_rr_d5", DirectionSampling::Brdf, true, true, true, 5},
                      FurnaceCase{"cosine_rr_unbounded", DirectionSampling::Cosine, false, false, true, -1},
                      FurnaceCase{"nee_rr_unbounded", DirectionSampling::Brdf, true, false, true, -1},
                      FurnaceCase{"mis_rr_unbounded", DirectionSampling::Brdf, true, true, true, -1}),
    [](const auto& tp) { return std::string(tp.param.name); });

// The course path tracer's rule (NEE also at the vertex at MaxRecursionDepth) adds exactly one more bounce of light,
// with uniform and with BRDF-sampled directions.
TEST(Furnace, CourseNeeAtTheLastVertexAddsOneBounce) {
  for (const bool importance : {false, true}) {
    CoursePathSettings s;
    s.importance_sampling = importance;
    s.nee = true;
    s.max_depth = 3;
    const SceneDesc scene = furnace_box(0.8f, Rgb(1.0f));
    const auto world = build_world(scene, {});
    const Estimate e = estimate_mean(*world, s, scene.cameras[0], 200000);
    const double want = expected(0.8, 1.0, 4);
    EXPECT_NEAR(e.mean, want, 4.5 * e.stderr_ + 1e-4 * want)
        << (importance ? "brdf" : "uniform") << ": mean " << e.mean << " +- " << e.stderr_ << ", expected " << want;
  }
}

// The course's RussianRoulette (CENG795 scenes) weights the direct light gathered at bounce k >= 1 by 2 - p_k,
// p_k = min(1, (a/pi)^k) in the furnace (its survival probability, from the product of the BRDF values a/pi).
// Without NEE that light is the emission found at bounce k; with NEE (also at the last vertex, course rule) it is
// NEE's one more bounce. Expected mode must reach this for every course strategy, bounded or not; the literal coin
// flips must reach the same value where their variance is finite (depth <= 2).
double course_expected(double a, bool nee, int max_depth) {
  double sum = nee ? 1.0 + a : 1.0, ak = a;
  const int last = max_depth < 0 ? 400 : max_depth;
  for (int k = 1; k <= last; ++k, ak *= a) {
    const double p = std::min(1.0, std::pow(a / kPi, double(k)));
    sum += (nee ? ak * a : ak) * (2.0 - p);
  }
  return sum;
}

TEST(Furnace, CourseRouletteReachesTheCourseEstimatorsExpectation) {
  struct Case {
    bool importance;
    bool nee;
    int max_depth;
    CourseRoulette mode;
  };
  const Case cases[] = {{false, false, -1, CourseRoulette::Expected}, {true, false, -1, CourseRoulette::Expected},
                        {false, true, -1, CourseRoulette::Expected},  {true, true, -1, CourseRoulette::Expected},
                        {true, false, 2, CourseRoulette::Expected},   {true, true, 2, CourseRoulette::Expected},
                        {false, false, 2, CourseRoulette::Literal},   {true, false, 2, CourseRoulette::Literal},
                        {true, true, 2, CourseRoulette::Literal}};
  const float albedo = 0.5f;
  const SceneDesc scene = furnace_box(albedo, Rgb(1.0f));
  const auto world = build_world(scene, {});
  for (const Case& c : cases) {
    CoursePathSettings cs;
    cs.importance_sampling = c.importance;
    cs.nee = c.nee;
    cs.roulette = c.mode;
    cs.max_depth = c.max_depth;
    const IntegratorSettings s = cs;
    const Estimate e = estimate_mean(*world, s, scene.cameras[0], 200000);
    const double want = course_expected(albedo, c.nee, c.max_depth);
    EXPECT_NEAR(e.mean, want, 4.5 * e.stderr_ + 1e-4 * want)
        << s.describe() << ": mean " << e.mean << " +- " << e.stderr_ << ", expected " << want;
    // Distinguishable from the unbiased answer at the same 4.5 sigma, so the test also proves the weighting is applied.
    if (c.max_depth < 0) {
      EXPECT_GT(e.mean - expected(albedo, 1.0, -1), 4.5 * e.stderr_);
    }
  }
}

// Course materials without a specular lobe compile to Lambertians (scenes/material_mapping.h): written as each
// Phong / Blinn-Phong form with the kd that gives albedo a (a/pi for the unnormalized forms, whose f is kd), the
// furnace still gives Le * sum_k a^k.
TEST(Furnace, ZeroSpecularCourseMaterialsKeepTheirAlbedo) {
  constexpr float kAlbedo = 0.6f;
  constexpr int kDepth = 4;
  struct Case {
    BrdfKind kind;
    bool normalized;
  };
  for (const Case c : {Case{BrdfKind::OriginalPhong, false}, Case{BrdfKind::ModifiedPhong, true},
                       Case{BrdfKind::OriginalBlinnPhong, false}, Case{BrdfKind::ModifiedBlinnPhong, false}}) {
    SceneDesc scene = furnace_box(kAlbedo, Rgb(1.0f));
    scene.brdfs[0].kind = c.kind;
    scene.brdfs[0].normalized = c.normalized;
    scene.brdfs[0].exponent = 20;
    scene.materials[0].diffuse = Rgb(c.normalized ? kAlbedo : kAlbedo / kPi);
    const auto world = build_world(scene, {});
    ASSERT_EQ(world->materials[0].describe(), "lambert");
    PathSettings s;
    s.max_depth = kDepth;
    s.russian_roulette = false;
    const Estimate e = estimate_mean(*world, s, scene.cameras[0], 200000);
    const double want = expected(kAlbedo, 1.0, kDepth);
    EXPECT_NEAR(e.mean, want, 4.5 * e.stderr_ + 1e-4 * want) << int(c.kind) << ": mean " << e.mean << " +- " << e.stderr_;
  }
}

// A convex Lambertian sphere under a constant infinite light L sees the sky over its whole upper hemisphere and
// nothing else, so every point of it sends a * L (one bounce; later bounces escape). Every strategy must find it:
// NEE through the light's own sampling, BRDF / cosine / uniform sampling through rays that leave the scene, MIS
// through both weighted by the light's direction density.
TEST(Furnace, ConvexSphereUnderAConstantInfiniteLight) {
  constexpr float kAlbedo = 0.6f;
  const Rgb sky(0.5f, 1.0f, 2.0f);
  SceneDesc s = lambertian_scene(kAlbedo, "sky.test");
  SphereDesc ball;
  ball.name = "ball";
  ball.radius = 1.0f;
  ball.material = 0;
  s.spheres.push_back(ball);
  s.infinite_lights.push_back({sky});
  CameraDesc cam;
  cam.position = {0, 0, 3};
  cam.use_fov = true;
  cam.fov_y_deg = 20;  // the ball fills the view
  cam.width = cam.height = 8;
  s.cameras.push_back(cam);
  const auto world = build_world(s, {});
  ASSERT_EQ(world->infinite_lights.size(), 1u);
  for (const char* name : {"uniform", "cosine", "brdf", "nee", "mis", "mis+rr"}) {
    PathSettings p = kiln_strategy(name, PathSettings{}, "test");
    p.rr_min_depth = 0;
    const Estimate e = estimate_mean(*world, p, s.cameras[0], 100000);
    EXPECT_NEAR(e.mean, kAlbedo * sky.r, 4.5 * e.stderr_ + 1e-5) << name << ": " << e.mean << " +- " << e.stderr_;
  }
}

// pbrt-style unit case: emission 1 - a makes the exact answer 1 for any albedo.
TEST(Furnace, UnitRadiance) {
  const SceneDesc scene = furnace_box(0.7f, Rgb(0.3f));
  const auto world = build_world(scene, {});
  PathSettings s;
  s.max_depth = -1;
  s.russian_roulette = true;
  const Estimate e = estimate_mean(*world, s, scene.cameras[0], 200000);
  EXPECT_NEAR(e.mean, 1.0, 4.5 * e.stderr_ + 1e-4);
}

// The pbrt-style unit sphere: a closed emitter of radiance 1 - a and albedo a seen from inside gives exactly 1, for
// any shape, so also for an ellipsoid. Kiln's LightSphere emits outward only (the course's definition), so this is a
// tessellated sphere whose triangles emit inward (their areas differ by ~8x, more under the ellipsoid's scale).
// Without NEE the answer does not depend on the shape; with NEE the light samples of a curved, unequal mesh do.
SceneDesc furnace_sphere(float albedo, Vec3f scale) {
  constexpr int kRings = 24, kSegments = 48;
  SceneDesc s = furnace_box(albedo, Rgb(1.0f - albedo));
  MeshDesc& m = s.meshes[0];
  m.name = "unit sphere";
  m.positions.clear();
  m.indices.clear();
  for (int i = 0; i <= kRings; ++i)
    for (int j = 0; j < kSegments; ++j) {
      const float theta = kPi * float(i) / kRings, phi = 2.0f * kPi * float(j) / kSegments;
      const Vec3f p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.push_back(p * scale);
    }
  auto vertex = [&](int i, int j) { return uint32_t(i * kSegments + (j % kSegments)); };
  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    const Vec3f pa = m.positions[a], pb = m.positions[b], pc = m.positions[c];
    if (length(cross(pb - pa, pc - pa)) == 0.0f) return;  // the poles' degenerate triangles
    // Wound so that (v1-v0)x(v2-v0) points to the centre: the emitting side faces inward.
    if (dot(cross(pb - pa, pc - pa), pa + pb + pc) > 0.0f) std::swap(b, c);
    m.indices.insert(m.indices.end(), {a, b, c});
  };
  for (int i = 0; i < kRings; ++i)
    for (int j = 0; j < kSegments; ++j) {
      add(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
      add(vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
    }
  return s;
}

TEST(Furnace, UnitSphereAndEllipsoidGiveOne) {
  const FurnaceCase cases[] = {{"uniform_rr", DirectionSampling::Uniform, false, false, true, -1},
                               {"cosine_rr", DirectionSampling::Cosine, false, false, true, -1},
                               {"nee_rr", DirectionSampling::Brdf, true, false, true, -1},
                               {"mis_rr", DirectionSampling::Brdf, true, true, true, -1}};
  for (const Vec3f scale : {Vec3f(1.0f), Vec3f(1.0f, 0.5f, 2.0f)})
    for (const FurnaceCase& fc : cases) {
      const SceneDesc scene = furnace_sphere(0.7f, scale);
      const auto world = build_world(scene, {});
      const Estimate e = estimate_mean(*world, settings_of(fc), scene.cameras[0], 200000);
      EXPECT_NEAR(e.mean, 1.0, 4.5 * e.stderr_ + 1e-4)
          << fc.name << (scale.y != 1.0f ? " ellipsoid" : " sphere") << ": mean " << e.mean << " +- " << e.stderr_;
    }
}

// The test must be able to fail: a deliberately wrong answer (one bounce fewer) is rejected.
// Kiln's roulette ends paths as its rule says, not only without bias: with roulette switched off an unbounded path
// runs kMaxPathVertices bounces, whose sum of a^k equals the unbounded one to float precision, so the radiance
// checks above cannot tell. Cosine sampling of a Lambertian of albedo a multiplies the throughput by exactly a, so
// the expected number of bounce rays per camera sample follows from the survival rule alone (below).
TEST(Furnace, KilnRouletteEndsPathsAtItsSurvivalRate) {
  constexpr double kAlbedo = 0.5;
  constexpr uint32_t kSamples = 100000;
  const SceneDesc scene = furnace_box(float(kAlbedo), Rgb(1.0f));
  const auto world = build_world(scene, {});
  PathSettings s;
  s.directions = DirectionSampling::Cosine;
  s.nee = false;
  s.mis = false;
  s.russian_roulette = true;
  s.rr_min_depth = 3;
  s.max_depth = -1;
  const Camera cam(scene.cameras[0]);
  const TraceContext tc(*world, cam, s);
  RayCounters c;
  double sum = 0, sum2 = 0;
  for (uint32_t i = 0; i < kSamples; ++i) {
    Sampler sampler(11, i % 8, i / 8 % 8, i);
    const Ray ray = cam.generate_ray(4.0f, 4.0f, sampler.next_2d());
    sampler.set_dimension(kFirstPathDimension);
    const uint64_t before = c.indirect;
    (void)trace(tc.ctx, ray, {0.5f, 0.5f}, sampler, c);
    const double bounces = double(c.indirect - before);
    sum += bounces;
    sum2 += bounces * bounces;
  }
  const Estimate e = estimate_from_sums(sum, sum2, kSamples);
  // Three bounces always; from the fourth scattering on, a path with throughput b goes on with probability √b and
  // carries √b, so its next vertex has a·√b (b = a^4 at the first). Every survival is one more bounce ray.
  double want = 3.0, b = std::pow(kAlbedo, 4), reach = 1.0;
  for (int k = 0; k < 100; ++k) {
    reach *= std::sqrt(b);
    want += reach;
    b = kAlbedo * std::sqrt(b);
  }
  EXPECT_NEAR(e.mean, want, 4.5 * e.stderr_) << "bounce rays per sample " << e.mean << " +- " << e.stderr_;
}

TEST(Furnace, DetectsAMissingBounce) {
  const SceneDesc scene = furnace_box(0.5f, Rgb(1.0f));
  const auto world = build_world(scene, {});
  PathSettings s;
  s.max_depth = 4;
  s.russian_roulette = false;
  const Estimate e = estimate_mean(*world, s, scene.cameras[0], 200000);
  EXPECT_GT(std::abs(e.mean - expected(0.5, 1.0, 5)), 4.5 * e.stderr_);
}

}  // namespace
}  // namespace kiln::test
