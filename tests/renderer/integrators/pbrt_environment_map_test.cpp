// pbrt-v4 image infinite lights in the renderer (renderer/world/environment_map.h): the equal-area furnace (a
// Lambertian ball of albedo a under a constant equal-area map, in a rotated frame, shows a L for every strategy);
// a 2:1 map is read as pbrt-v3's lat-long (z up) with a warning, any other non-square map is an error naming the file
// and line; "illuminance" as pbrt-v4 normalises it; 8-bit maps are sRGB-decoded as pbrt decodes them.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/equal_area.h"
#include "core/error.h"
#include "renderer/image_io/image_io.h"
#include "renderer/test_scenes.h"
#include "renderer/world/environment_map.h"

namespace kiln::test {
namespace {

constexpr float kAlbedo = 0.6f;
constexpr double kPiD = 3.14159265358979323846;

std::string write_map(const std::string& name, const Image& img) {
  const std::string path = tmp_dir("pbrt_envmap") + "/" + name;
  write_exr(path, img, {}, {});
  return path;
}

Image constant(int w, int h, Rgb c) {
  Image img(w, h);
  for (Rgb& p : img.pixels()) p = c;
  return img;
}

EnvLightDesc pbrt_map(const std::string& path) {
  EnvLightDesc e;
  e.image_path = path;
  e.element = "line 9 (LightSource \"infinite\")";
  e.format = EnvMapFormat::EqualArea;
  e.lat_long_if_not_square = true;
  e.light_to_world = Transform::rotate(-90.0f, {1, 0, 0});
  return e;
}

SceneDesc ball_under(const EnvLightDesc& env) {
  SceneDesc s = ball_scene(kAlbedo, "env.pbrt");
  s.env_lights.push_back(env);
  return s;
}

TEST(Furnace, ConvexSphereUnderAConstantEqualAreaMap) {
  const Rgb sky(0.5f, 1.0f, 2.0f);
  const SceneDesc s = ball_under(pbrt_map(write_map("constant_square.exr", constant(32, 32, sky))));
  const auto world = build_world(s, {});
  ASSERT_EQ(std::get<ImageInfiniteLight>(world->lights.at(0)).layout(), EnvMapLayout::EqualArea);
  for (const char* name : {"uniform", "brdf", "nee", "mis", "mis+rr"}) {
    PathSettings p = kiln_strategy(name, PathSettings{}, "test");
    p.rr_min_depth = 0;
    const Estimate e = estimate_mean(*world, p, s.cameras[0], 100000);
    EXPECT_NEAR(e.mean, kAlbedo * sky.r, 4.5 * e.stderr_ + 1e-5) << name << ": " << e.mean << " +- " << e.stderr_;
  }
}

TEST(PbrtEnvironmentMap, ANonSquareTwoToOneMapIsReadAsPbrtV3LatLong) {
  // Columns by u, rows by v, each texel a distinct value: pbrt-v3's lat-long has +z at the top row (v = 0), phi
  // from +x (u = 0) towards +y (u = 1/4).
  Image img(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) img.at(x, y) = Rgb(float(1 + x + 8 * y));
  EnvLightDesc env = pbrt_map(write_map("latlong.exr", img));
  env.light_to_world = Transform();
  const SceneDesc s = ball_under(env);
  const auto world = build_world(s, {});
  ASSERT_EQ(world->warnings.size(), 1u);
  EXPECT_NE(world->warnings[0].find("env.pbrt: line 9 (LightSource \"infinite\")"), std::string::npos);
  EXPECT_NE(world->warnings[0].find("is 8 x 4, not square"), std::string::npos) << world->warnings[0];
  EXPECT_NE(world->warnings[0].find("lat-long"), std::string::npos);
  const auto& light = std::get<ImageInfiniteLight>(world->lights.at(0));
  EXPECT_EQ(light.layout(), EnvMapLayout::LatLong);
  // pbrt-v3's InfiniteAreaLight lookup, written out: u = phi / 2 pi (phi in [0, 2 pi) from +x), v = theta / pi.
  const auto pbrt_v3_texel = [&](Vec3f d) {
    double phi = std::atan2(double(d.y), double(d.x));
    if (phi < 0.0) phi += 2.0 * kPiD;
    const double theta = std::acos(double(d.z));
    return img.at(int(phi / (2.0 * kPiD) * 8.0), int(theta / kPiD * 4.0));
  };
  for (const Vec3f d : {Vec3f(0.1f, 0.05f, 1.0f), Vec3f(0.2f, 0.35f, -0.07f), Vec3f(-1.0f, 0.01f, -0.5f),
                        Vec3f(0.3f, -0.8f, 0.4f), Vec3f(-0.2f, -0.1f, -0.9f)}) {
    const Vec3f u = normalize(d);
    EXPECT_EQ(light.radiance(u), pbrt_v3_texel(u)) << u.x << " " << u.y << " " << u.z;
  }
}

TEST(PbrtEnvironmentMap, OtherNonSquareMapsAndUnreadableFilesNameFileAndLine) {
  const SceneDesc s = ball_under(pbrt_map(write_map("wide.exr", constant(12, 4, Rgb(1.0f)))));
  try {
    build_world(s, {});
    ADD_FAILURE() << "a 3:1 equal-area map builds";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("env.pbrt: line 9 (LightSource \"infinite\")"), std::string::npos) << m;
    EXPECT_NE(m.find("is 12 x 4: an equal-area map must be square"), std::string::npos) << m;
  }
  const std::string junk = tmp_dir("pbrt_envmap") + "/junk.exr";
  std::ofstream(junk) << "not an image";
  EXPECT_THROW(build_world(ball_under(pbrt_map(junk)), {}), Error);
}

TEST(PbrtEnvironmentMap, IlluminanceIsNormalisedAsPbrtV4Does) {
  // pbrt-v4 sums luminance x cos over the upper hemisphere's texels times 2 pi / texels: half the illuminance the
  // map gives a surface facing its zenith (pi L for a constant map). Its maps end up giving twice "illuminance".
  constexpr float kE = 3.0f;
  const Image map = constant(64, 64, Rgb(0.8f));
  EXPECT_NEAR(pbrt_map_illuminance(map, EnvMapLayout::EqualArea), 0.5 * kPiD * 0.8, 2e-3);
  EXPECT_NEAR(pbrt_map_illuminance(constant(128, 64, Rgb(0.8f)), EnvMapLayout::LatLong), 0.5 * kPiD * 0.8, 2e-3);
  EnvLightDesc env = pbrt_map(write_map("constant64.exr", map));
  env.illuminance = kE;
  env.scale = 2.0f;
  std::vector<std::string> warnings;
  const ImageInfiniteLight light = make_environment_light(ball_under(env), env, 1.0f,
                                                          EnvMapSampling::ImportanceSampled, warnings);
  EXPECT_NEAR(light.radiance({0, 1, 0}).g, 2.0 * kE / (0.5 * kPiD), 2e-3 * kE);
}

TEST(PbrtEnvironmentMap, EightBitMapsAreSrgbDecoded) {
  const std::string path = tmp_dir("pbrt_envmap") + "/grey.png";
  std::vector<uint8_t> rgb(4 * 4 * 3, 128);
  write_png(path, rgb, 4, 4);
  std::vector<std::string> warnings;
  EnvLightDesc env = pbrt_map(path);
  const ImageInfiniteLight pbrt = make_environment_light(ball_under(env), env, 1.0f, EnvMapSampling::ImportanceSampled,
                                                         warnings);
  EXPECT_NEAR(pbrt.radiance({0, 0, 1}).r, srgb_to_linear(128.0f / 255.0f), 1e-6f);
  env.format = EnvMapFormat::LatLongYUp;  // the course's maps are read as stored
  const ImageInfiniteLight course = make_environment_light(ball_under(env), env, 1.0f,
                                                           EnvMapSampling::ImportanceSampled, warnings);
  EXPECT_NEAR(course.radiance({0, 0, 1}).r, 128.0f / 255.0f, 1e-6f);
}

}  // namespace
}  // namespace kiln::test
