// Raw accelerator rate on the very rays a render asks for: a one-thread, one-sample render of the bundled
// killeroo_path.xml (640x480) at a Loop subdivision level records every query (camera rays are those of the first pass over the pixels, the other
// closest-hit queries are bounces, occlusion queries are shadow rays), then the benchmark traces them again in a
// tight loop. `kiln profile scenes/killeroo_path.xml --subdivide N --spp 1 --threads 1` renders the same rays and
// reports the in-render rate of each kind ("query Mrays/s"); their ratio is what Kiln's shading, sampling and cache
// traffic cost the accelerator.
//   kiln_bench --benchmark_filter=AccelReplay --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Args = (subdivision level, kind: 0 primary, 1 bounce, 2 shadow).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include <tbb/global_control.h>

#include "renderer/world/camera.h"
#include "renderer/film/film.h"
#include "renderer/render/render.h"
#include "renderer/integrators/rules.h"
#include "renderer/world/world.h"
#include "renderer/bench/trace_loop.h"
#include "scenes/loader.h"

namespace kiln {
namespace {

// Forwards to the real accelerator and keeps every ray it is asked (the render runs on one thread).
class RecordingAccel final : public Accelerator {
 public:
  explicit RecordingAccel(const Accelerator& inner) : inner_(inner) {}
  bool intersect(const Ray& ray, Hit& hit) const override {
    closest_.push_back(ray);
    return inner_.intersect(ray, hit);
  }
  bool occluded(const Ray& ray) const override {
    shadow_.push_back(ray);
    return inner_.occluded(ray);
  }
  AccelStats stats() const override { return inner_.stats(); }
  mutable std::vector<Ray> closest_, shadow_;

 private:
  const Accelerator& inner_;
};

struct Replay {
  SceneDesc scene;
  std::unique_ptr<World> world;
  std::vector<Ray> rays[3];  // primary, bounce, shadow

  explicit Replay(int levels) {
    LoadOptions lo;
    lo.subdivide = levels;
    scene = load_scene(std::string(KILN_BUNDLED_SCENES_DIR) + "/killeroo_path.xml", lo);
    world = build_world(scene, {});
    const CameraDesc& cd = scene.cameras.front();
    const Camera camera(cd);
    const IntegratorSettings settings = camera_settings(cd, scene, scene.rules, {}, world->features);

    std::unique_ptr<Accelerator> real = std::move(world->accel);
    world->accel = std::make_unique<RecordingAccel>(*real);
    {
      const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
      Film film(camera.width(), camera.height());
      RenderOptions ro;
      ro.spp_total = 1;
      render_samples(*world, camera, settings, ro, 0, 1, film);
    }
    const std::unique_ptr<Accelerator> recorder = std::exchange(world->accel, std::move(real));
    auto& rec = static_cast<RecordingAccel&>(*recorder);
    // The scene's camera is a pinhole: camera rays start exactly at its eye, bounces never do.
    const Vec3f eye = camera.generate_ray(0.5f, 0.5f, Vec2f(0.5f, 0.5f)).o;
    for (const Ray& r : rec.closest_) (r.o == eye ? rays[0] : rays[1]).push_back(r);
    rays[2] = std::move(rec.shadow_);
  }
};

const Replay& replay(int levels) {
  static std::mutex mu;
  static std::map<int, std::unique_ptr<Replay>> cache;
  const std::lock_guard lock(mu);
  auto& r = cache[levels];
  if (!r) r = std::make_unique<Replay>(levels);
  return *r;
}

void BM_AccelReplay(benchmark::State& state) {
  const Replay& rp = replay(int(state.range(0)));
  const int kind = int(state.range(1));
  trace_rays_benchmark(state, *rp.world->accel, rp.rays[kind], kind);
}

BENCHMARK(BM_AccelReplay)
    ->Name("AccelReplay/embree")
    ->ArgsProduct({{0, 2, 4}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace kiln
