// A world is immutable once built: two renders of one world, two cameras at once, give exactly the images each gives
// alone. The scene has a texture filtered over each hit's footprint, which is measured in the rendering camera's
// pixels (renderer/world/hit_textures.h): state a render kept in the world would leak from one camera into the other.
// Runs under ThreadSanitizer in CI (.ci/tsan.sh).
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "renderer/image_io/image_io.h"
#include "renderer/render_util.h"
#include "renderer/texture/scene_textures.h"

namespace kiln::test {
namespace {

constexpr int kTexels = 64;
constexpr uint32_t kSpp = 4;

// White noise: every MIP level differs from the others, so a footprint of another size reads other values.
std::string write_noise_texture() {
  Image img(kTexels, kTexels);
  Rng rng(1234, 0);
  for (Rgb& p : img.pixels()) p = Rgb(rng.next_float(), rng.next_float(), rng.next_float());
  const std::string path = tmp_dir("concurrent_render") + "/noise.exr";
  write_exr(path, img, {}, {});
  return path;
}

CameraDesc camera(const std::string& id, Vec3f position, float fov_y_deg, int size) {
  CameraDesc c;
  c.id = id;
  c.position = position;
  c.gaze = Vec3f(0, 0, -1) - position;
  c.up = {0, 1, 0};
  c.use_fov = true;
  c.fov_y_deg = fov_y_deg;
  c.width = c.height = size;
  return c;
}

// A trilinear-filtered noise wall (its k_d) lit by a point light, under Kiln's rules, seen by a narrow low-resolution
// camera and a wide high-resolution one: their pixel footprints on the wall differ by a factor of several.
SceneDesc textured_wall() {
  SceneDesc s = lambertian_scene(0.8f, "concurrent.xml");
  TextureDesc t;
  t.name = "Texture id=1";
  t.source = TextureSource::Image;
  t.image_path = write_noise_texture();
  t.filter = TextureFilter::Trilinear;
  t.decal = DecalMode::ReplaceKd;
  s.textures.push_back(t);
  MeshDesc m;
  m.name = "Mesh id=1";
  m.positions = {{-2, -2, -1}, {2, -2, -1}, {2, 2, -1}, {-2, 2, -1}};
  m.uvs = {{0, 4}, {4, 4}, {4, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = 0;
  m.textures = {0};
  s.meshes.push_back(m);
  s.point_lights.push_back(PointLightDesc{{0.5f, 0.5f, 2.0f}, Rgb(20.0f)});
  s.cameras.push_back(camera("narrow", {0.2f, 0.1f, 3.0f}, 20.0f, 24));
  s.cameras.push_back(camera("wide", {-0.3f, 0.0f, 2.0f}, 70.0f, 48));
  return s;
}

bool bit_identical(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Rgb)) == 0;
}

struct Job {
  Camera camera;
  IntegratorSettings settings;
  RenderOptions options;
  Film film;
  Job(const CameraDesc& cd, const SceneDesc& s, const World& w)
      : camera(cd), settings(scene_settings(cd, s, w.features)), film(camera.width(), camera.height()) {
    options.seed = 3;
    options.spp_total = kSpp;
    options.tile_size = 4;
  }
  void render(const World& w) { render_samples(w, camera, settings, options, 0, kSpp, film); }
};

// Whether the pixel-centre rays of job's camera change value when shaded with the pixel spread of `other`.
bool spread_matters(const World& w, const Job& job, const Camera& other) {
  TraceContext own(w, job.camera, job.settings), swapped(w, job.camera, job.settings);
  swapped.ctx.pixel_spread = other.pixel_spread();
  RayCounters c;
  for (int y = 0; y < job.camera.height(); ++y)
    for (int x = 0; x < job.camera.width(); ++x) {
      const Ray ray = job.camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f, {0.5f, 0.5f});
      const Vec2f film = pixel_film_position(x, y, job.camera.width(), job.camera.height());
      Sampler s1(1, uint32_t(x), uint32_t(y), 0), s2(1, uint32_t(x), uint32_t(y), 0);
      s1.set_dimension(kFirstPathDimension);
      s2.set_dimension(kFirstPathDimension);
      if (!(trace(own.ctx, ray, film, s1, c) == trace(swapped.ctx, ray, film, s2, c))) return true;
    }
  return false;
}

TEST(ConcurrentRenders, TwoCamerasOfOneWorldEqualTheirRendersAlone) {
  const SceneDesc scene = textured_wall();
  const auto world = build_scene_world(scene);
  ASSERT_EQ(world->textures->stats().footprint_bindings, 1u);

  Job narrow_alone(scene.cameras[0], scene, *world), wide_alone(scene.cameras[1], scene, *world);
  narrow_alone.render(*world);
  wide_alone.render(*world);
  // The cameras see the wall at different footprints: the narrow camera's rays shaded with the wide camera's pixel
  // spread give other values, so a render that used the other's would show.
  ASSERT_TRUE(spread_matters(*world, narrow_alone, wide_alone.camera));

  // At once, on two threads. The narrow render waits after its first pixel until the wide one has begun, so that the
  // two overlap (the wide one's start, where per-render state would be set up, falls inside the narrow one).
  Job narrow(scene.cameras[0], scene, *world), wide(scene.cameras[1], scene, *world);
  std::atomic<int> wide_pixels{0}, narrow_pixels{0};
  std::atomic<bool> overlapped{false};
  wide.options.on_pixel_done = [&] { wide_pixels.fetch_add(1); };
  narrow.options.on_pixel_done = [&] {
    if (narrow_pixels.fetch_add(1) != 0) return;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (wide_pixels.load() == 0 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
    overlapped.store(wide_pixels.load() > 0);
  };
  std::thread a([&] { narrow.render(*world); });
  std::thread b([&] { wide.render(*world); });
  a.join();
  b.join();
  EXPECT_TRUE(overlapped.load()) << "the renders did not overlap";
  EXPECT_TRUE(bit_identical(narrow.film.mean(), narrow_alone.film.mean())) << "narrow camera";
  EXPECT_TRUE(bit_identical(wide.film.mean(), wide_alone.film.mean())) << "wide camera";
}

}  // namespace
}  // namespace kiln::test
