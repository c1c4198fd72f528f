// Environment maps (SphericalDirectionalLight) in the integrators: a constant map is the furnace (a convex diffuse
// sphere of albedo a shows a L, as under the constant InfiniteLight), for Kiln's strategies and for the course path
// tracer's uniform-hemisphere rule; on a non-constant map BRDF sampling, NEE and MIS agree; camera rays that miss see
// the map; a missing or unreadable map is an error naming the file and the element.
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "renderer/test_scenes.h"
#include "renderer/image_io/image_io.h"

namespace kiln::test {
namespace {

constexpr float kAlbedo = 0.6f;

std::string write_map(const std::string& name, const Image& img) {
  const std::string path = tmp_dir("envmap") + "/" + name;
  write_exr(path, img, {}, {});
  return path;
}

Image constant_map(Rgb c) {
  Image img(32, 16);
  for (Rgb& p : img.pixels()) p = c;
  return img;
}

// A bright sun above and to the side, a sky gradient, a dark ground: what importance sampling is for.
Image sky_map() {
  Image img(64, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      img.at(x, y) = y < 16 ? Rgb(0.3f + 0.02f * float(y), 0.5f, 0.9f) : Rgb(0.05f, 0.04f, 0.03f);
  for (int y = 5; y < 7; ++y)
    for (int x = 40; x < 42; ++x) img.at(x, y) = Rgb(400.0f, 380.0f, 300.0f);
  return img;
}

// A Lambertian ball of albedo kAlbedo under the map, filling the view.
SceneDesc ball_under(const std::string& map) {
  SceneDesc s = ball_scene(kAlbedo, "env.test");
  s.env_lights.push_back({map, "SphericalDirectionalLight id=1"});
  return s;
}

TEST(Furnace, ConvexSphereUnderAConstantEnvironmentMap) {
  const Rgb sky(0.5f, 1.0f, 2.0f);
  const SceneDesc s = ball_under(write_map("constant.exr", constant_map(sky)));
  const auto world = build_world(s, {});
  ASSERT_EQ(world->infinite_lights.size(), 1u);
  ASSERT_TRUE(world->features & kFeatureEnvironmentMap);
  for (const char* name : {"uniform", "cosine", "brdf", "nee", "mis", "mis+rr"}) {
    PathSettings p = kiln_strategy(name, PathSettings{}, "test");
    p.rr_min_depth = 0;
    const Estimate e = estimate_mean(*world, p, s.cameras[0], 100000);
    EXPECT_NEAR(e.mean, kAlbedo * sky.r, 4.5 * e.stderr_ + 1e-5) << name << ": " << e.mean << " +- " << e.stderr_;
  }
}

TEST(Furnace, CoursePathTracerUnderAConstantEnvironmentMap) {
  // The course's rule: the map sampled uniformly over the hemisphere (pdf 1/2pi), with and without NEE.
  const Rgb sky(0.5f, 1.0f, 2.0f);
  const SceneDesc s = ball_under(write_map("constant_course.exr", constant_map(sky)));
  WorldOptions wo;
  wo.env_map_sampling = env_map_sampling(SceneRules::Ceng795Course, {});
  ASSERT_EQ(wo.env_map_sampling, EnvMapSampling::UniformHemisphere);
  const auto world = build_world(s, wo);
  for (bool nee : {false, true}) {
    CoursePathSettings c;
    c.nee = nee;
    c.max_depth = 4;
    const Estimate e = estimate_mean(*world, c, s.cameras[0], 100000);
    EXPECT_NEAR(e.mean, kAlbedo * sky.r, 4.5 * e.stderr_ + 1e-5) << "nee " << nee << ": " << e.mean;
  }
}

TEST(EnvironmentMap, BrdfNeeAndMisAgreeOnANonConstantMap) {
  const SceneDesc s = ball_under(write_map("sky.exr", sky_map()));
  const auto world = build_world(s, {});
  std::vector<std::pair<std::string, Estimate>> results;
  for (const char* name : {"brdf", "nee", "mis"}) {
    PathSettings p = kiln_strategy(name, PathSettings{}, "test");
    p.max_depth = 1;  // one bounce: the ball is convex, nothing else to hit
    results.push_back({name, estimate_mean(*world, p, s.cameras[0], 200000)});
  }
  for (size_t i = 1; i < results.size(); ++i) {
    const Estimate a = results[0].second, b = results[i].second;
    EXPECT_NEAR(a.mean, b.mean, 4.5 * std::hypot(a.stderr_, b.stderr_))
        << results[0].first << " " << a.mean << " +- " << a.stderr_ << " vs " << results[i].first << " " << b.mean
        << " +- " << b.stderr_;
  }
  // Importance sampling finds the sun: NEE's error is far below BRDF sampling's.
  EXPECT_LT(results[1].second.stderr_, 0.5 * results[0].second.stderr_);
}

TEST(EnvironmentMap, CameraRaysThatMissSeeTheMap) {
  SceneDesc s = ball_under(write_map("sky_miss.exr", sky_map()));
  s.spheres.clear();
  const auto world = build_world(s, {});
  const ImageInfiniteLight& light = std::get<ImageInfiniteLight>(world->lights[size_t(world->infinite_lights[0])]);
  for (IntegratorSettings settings : {IntegratorSettings(PathSettings{}), IntegratorSettings(CourseRaySettings{}),
                                      IntegratorSettings(CoursePathSettings{})}) {
    Sampler sampler(1, 0, 0, 0);
    RayCounters c;
    const Ray r{{0, 0, 0}, normalize(Vec3f(0.3f, 0.4f, -1.0f))};
    const Camera camera(s.cameras[0]);
    const TraceContext tc(*world, camera, settings);
    EXPECT_EQ(trace(tc.ctx, r, {0.5f, 0.5f}, sampler, c), light.radiance(r.d)) << settings.describe();
  }
}

TEST(EnvironmentMap, MissingOrUnreadableMapNamesFileAndElement) {
  const std::string dir = tmp_dir("envmap_bad");
  const std::string scene = dir + "/scene.xml";
  auto write_scene = [&](const std::string& map) {
    std::ofstream(scene) << "<Scene><Cameras><Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
                            "<NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>"
                            "<ImageResolution>4 4</ImageResolution><ImageName>x.exr</ImageName></Camera></Cameras>"
                            "<Lights><SphericalDirectionalLight id=\"1\"><EnvMapName>"
                         << map << "</EnvMapName></SphericalDirectionalLight></Lights><Materials/></Scene>";
  };
  write_scene("absent.exr");
  try {
    load_scene(scene);
    ADD_FAILURE() << "a missing map loads";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("absent.exr"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("SphericalDirectionalLight id=1"), std::string::npos) << e.what();
  }
  std::ofstream(dir + "/garbage.exr") << "not an image";
  write_scene("garbage.exr");
  const SceneDesc s = load_scene(scene);
  try {
    build_world(s, {});
    ADD_FAILURE() << "an unreadable map builds";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("garbage.exr"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("SphericalDirectionalLight id=1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace kiln::test
