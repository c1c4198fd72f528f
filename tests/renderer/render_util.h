// Helpers for renderer tests: scenes built in code and direct access to the integrators.
#pragma once
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/rng.h"
#include "renderer/world/camera.h"
#include "renderer/film/film.h"
#include "renderer/film/pixel_filter.h"
#include "renderer/image_io/image_io.h"
#include "renderer/integrators/integrator.h"
#include "renderer/render/render.h"
#include "renderer/integrators/rules.h"
#include "renderer/world/world.h"
#include "scenes/loader.h"

namespace kiln::test {

inline std::string shared_dir() { return KILN_SHARED_DIR; }
inline bool have_shared() { return std::filesystem::exists(shared_dir() + "/scenes/ceng795"); }
inline std::string tmp_dir(const std::string& sub) {
  const std::string d = std::string(KILN_TEST_TMP) + "/" + sub;
  std::filesystem::create_directories(d);
  return d;
}

// Runs `kiln ARGS` (the binary under test) and returns its exit code and its stdout and stderr together.
inline std::pair<int, std::string> run_kiln_command(const std::string& args) {
  std::string out;
  FILE* p = popen((std::string(KILN_BINARY) + " " + args + " 2>&1").c_str(), "r");
  if (!p) return {-1, out};
  char buf[4096];
  while (fgets(buf, sizeof buf, p)) out += buf;
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// `kiln ARGS`'s exit code and its stdout and stderr together, as the CLI tests check them.
struct RunResult {
  int exit_code = -1;
  std::string output;
};
inline RunResult run_kiln(const std::string& args) {
  auto [code, output] = run_kiln_command(args);
  return {code, std::move(output)};
}

// A scene with one material, material 0: a Lambertian of the given albedo (shapes, lights and cameras to be added).
inline SceneDesc lambertian_scene(float albedo, const std::string& source_path = "") {
  SceneDesc s;
  s.format = "test";
  s.source_path = source_path;
  BrdfDesc lambert;
  lambert.kind = BrdfKind::Lambert;
  s.brdfs.push_back(lambert);
  MaterialDesc m;
  m.brdf = 0;
  m.diffuse = Rgb(albedo);
  s.materials.push_back(m);
  return s;
}

// A closed cube [-1,1]^3 whose faces are one LightMesh emitting Le inward, with a Lambertian interior of albedo a.
// Seen from inside, every strategy must give Le * sum_{k=0..D} a^k (D bounces), i.e. Le / (1 - a) unbounded.
inline SceneDesc furnace_box(float albedo, Rgb le) {
  SceneDesc s = lambertian_scene(albedo);
  MeshDesc box;
  box.name = "furnace";
  box.positions = {{-1, -1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1}};
  // Winding chosen so that (v1-v0)x(v2-v0) points into the box on every face.
  const uint32_t one_based[] = {1, 2, 3, 1, 3, 4, 5, 7, 6, 5, 8, 7, 1, 4, 8, 1, 8, 5,
                                1, 5, 6, 1, 6, 2, 4, 3, 7, 4, 7, 8, 2, 6, 7, 2, 7, 3};
  for (uint32_t i : one_based) box.indices.push_back(i - 1);
  box.material = 0;
  box.emission = le;
  s.meshes.push_back(box);
  CameraDesc cam;
  cam.id = "1";
  cam.position = {0.1f, -0.2f, 0.3f};
  cam.gaze = {0, 0, -1};
  cam.up = {0, 1, 0};
  cam.use_fov = true;
  cam.fov_y_deg = 90;
  cam.width = cam.height = 8;
  s.cameras.push_back(cam);
  return s;
}

// The world as kiln render builds it under the scene's own rules (their ellipsoid-light density).
inline std::unique_ptr<World> build_scene_world(const SceneDesc& scene) {
  WorldOptions wo;
  wo.ellipsoid_pdf = ellipsoid_pdf(scene.rules, {});
  return build_world(scene, wo);
}

// The settings the scene's own rules give camera cd (renderer/integrators/rules.h), without command-line overrides.
inline IntegratorSettings scene_settings(const CameraDesc& cd, const SceneDesc& scene, uint32_t features = kFeatureAll) {
  return camera_settings(cd, scene, scene.rules, {}, features);
}

// Camera 0 of a scene as `kiln render` renders it (the scene's rules and pixel filter), samples [0, spp): the film's
// mean. stats receives the render's counters when given.
inline Image render_like_kiln(const SceneDesc& scene, const World& w, uint32_t spp, uint64_t seed,
                              RenderStats* stats = nullptr) {
  const CameraDesc& cd = scene.cameras.at(0);
  const Camera cam(cd);
  Film film(cam.width(), cam.height());
  RenderOptions ro;
  ro.seed = seed;
  ro.spp_total = spp;
  ro.filter = pixel_filter_for(cd, std::nullopt);
  const RenderStats rs = render_samples(w, cam, scene_settings(cd, scene, w.features), ro, 0, spp, film);
  if (stats) *stats = rs;
  return film.mean();
}

// The bundled default scene at res x res under each integrator: Kiln's path tracer (its own rules), the course path
// tracer (the CENG795 rules with every RendererParams flag: literal course roulette, NEE at the last vertex, the
// Fresnel split) and the course ray tracer.
struct RuleCase {
  const char* name;
  SceneDesc scene;
};

inline std::vector<RuleCase> default_scene_rule_cases(int res) {
  SceneDesc kiln = load_scene(std::string(KILN_SOURCE_DIR) + "/scenes/default.xml");
  kiln.cameras[0].width = kiln.cameras[0].height = res;
  SceneDesc course_path = kiln;
  course_path.rules = SceneRules::Ceng795Course;
  course_path.cameras[0].renderer = RendererKind::PathTracing;
  course_path.cameras[0].pt = PathTracingFlags{true, true, true};
  SceneDesc course_rays = kiln;
  course_rays.rules = SceneRules::Ceng795Course;
  course_rays.cameras[0].renderer = RendererKind::RayTracing;
  return {{"kiln", kiln}, {"course_path", course_path}, {"course_rays", course_rays}};
}

// A W x H texture image in the tests' folder: float EXR whose texel (x, y) (y = 0 the top row) is f(x, y).
template <typename F>
inline std::string write_test_exr(const std::string& name, int w, int h, F f) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.at(x, y) = f(x, y);
  const std::string path = tmp_dir("textures") + "/" + name;
  write_exr(path, img, {}, {});
  return path;
}

// The angle between two directions, in radians.
inline float angle_between(Vec3f a, Vec3f b) {
  return std::acos(std::clamp(dot(normalize(a), normalize(b)), -1.0f, 1.0f));
}

struct Estimate {
  double mean = 0, stderr_ = 0;
};

// Mean and standard error of n samples from their sum and sum of squares.
inline Estimate estimate_from_sums(double sum, double sum2, double n) {
  Estimate e;
  e.mean = sum / n;
  e.stderr_ = std::sqrt(std::max(0.0, sum2 / n - e.mean * e.mean) / (n - 1.0));
  return e;
}

// A render context for tests that call the integrators (trace) directly: the camera's, with default options and a
// film the integrators do not write. It keeps its own copy of the settings, so a temporary may be passed.
struct TraceContext {
  IntegratorSettings settings;
  RenderOptions options;
  Film film{1, 1};
  RenderContext ctx;
  TraceContext(const World& w, const Camera& camera, IntegratorSettings s)
      : settings(std::move(s)), ctx(w, camera, settings, options, film) {}
};

// Mean luminance-free (red channel) estimate over n independent camera samples through random pixels.
inline Estimate estimate_mean(const World& w, const IntegratorSettings& s, const CameraDesc& cd, uint32_t n,
                              uint64_t seed = 7) {
  const Camera cam(cd);
  const TraceContext tc(w, cam, s);
  RayCounters c;
  double sum = 0, sum2 = 0;
  for (uint32_t i = 0; i < n; ++i) {
    Sampler sampler(seed, i % 64, i / 64, i);
    const Vec2f px = sampler.next_2d();
    const Ray ray = cam.generate_ray(px.x * float(cam.width()), px.y * float(cam.height()), sampler.next_2d());
    sampler.set_dimension(kFirstPathDimension);
    const Vec2f film = pixel_film_position(int(px.x * float(cam.width())), int(px.y * float(cam.height())),
                                           cam.width(), cam.height());
    const double v = trace(tc.ctx, ray, film, sampler, c).r;
    sum += v;
    sum2 += v * v;
  }
  return estimate_from_sums(sum, sum2, n);
}

// Renders camera 0 of a scene in full (optionally cropped/resized by the caller through the SceneDesc).
inline Image render_image(const World& w, const CameraDesc& cd, const IntegratorSettings& s, uint32_t spp,
                          uint64_t seed = 0, int threads = 0, bool reverse = false) {
  std::unique_ptr<tbb::global_control> gc;
  if (threads > 0) gc = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const Camera cam(cd);
  Film film(cam.width(), cam.height());
  RenderOptions ro;
  ro.seed = seed;
  ro.spp_total = spp;
  ro.reverse_tile_order = reverse;
  render_samples(w, cam, s, ro, 0, spp, film);
  return film.mean();
}

// Mean luminance of each block x block tile of camera cd (row-major) over spp samples of each of its pixels, with its
// standard error. Rendered with the world's feature mask.
inline std::vector<Estimate> block_estimates(const World& w, const CameraDesc& cd, IntegratorSettings s, uint32_t spp,
                                             uint64_t seed, int block) {
  s.features = w.features;
  const Camera cam(cd);
  const TraceContext tc(w, cam, s);
  const int bw = cam.width() / block, bh = cam.height() / block;
  std::vector<Estimate> out(size_t(bw * bh));
  tbb::parallel_for(0, int(out.size()), [&](int b) {
    const int bx = b % bw, by = b / bw;
    RayCounters c;
    double sum = 0, sum2 = 0;
    for (int py = by * block; py < (by + 1) * block; ++py)
      for (int px = bx * block; px < (bx + 1) * block; ++px)
        for (uint32_t i = 0; i < spp; ++i) {
          Sampler sampler(seed, uint32_t(px), uint32_t(py), i);
          sampler.set_dimension(kPixelDimension);
          const Vec2f u = sampler.next_2d();
          const Ray ray = cam.generate_ray(float(px) + u.x, float(py) + u.y, sampler.next_2d());
          sampler.set_dimension(kFirstPathDimension);
          const double v =
              trace(tc.ctx, ray, pixel_film_position(px, py, cam.width(), cam.height()), sampler, c).luminance();
          sum += v;
          sum2 += v * v;
        }
    out[size_t(b)] = estimate_from_sums(sum, sum2, double(block * block) * spp);
  });
  return out;
}

// The largest |z| over blocks between two sets of block estimates, and where it occurred.
struct Worst {
  double z = 0;
  int block = -1;
};
inline Worst worst_block(const std::vector<Estimate>& a, const std::vector<Estimate>& b) {
  Worst w;
  for (size_t i = 0; i < a.size(); ++i) {
    const double se = std::hypot(a[i].stderr_, b[i].stderr_);
    const double z = se > 0 ? std::abs(a[i].mean - b[i].mean) / se : (a[i].mean == b[i].mean ? 0.0 : INFINITY);
    if (z > w.z) w = {z, int(i)};
  }
  return w;
}

}  // namespace kiln::test
