// Accelerator benchmarks: build time and single-thread ray throughput (coherent primary, incoherent diffuse bounce,
// shadow rays to a point light) of Embree and the in-house BVH on the killeroo mesh and its Loop subdivisions.
//   kiln_bench --benchmark_filter=Accel --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Arg = Loop subdivision levels (0 = the control mesh). Falls back to a generated icosphere when the shared
// killeroo file is absent.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>

#include "core/frame.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "renderer/accel/bvh.h"
#include "renderer/accel/embree_accel.h"
#include "renderer/accel/surface_point.h"
#include "renderer/accel/shape_bounds.h"
#include "renderer/bench/trace_loop.h"
#include "scenes/ply_loader.h"
#include "scenes/subdivision.h"

namespace kiln {
namespace {

constexpr int kImageSide = 256;          // primary rays per pass = kImageSide^2
constexpr float kCameraDistance = 0.6f;  // times the scene diagonal: the mesh fills most of the 53-degree view

MeshDesc icosphere_desc(int levels) {
  // Fallback mesh: an octahedron refined by Loop subdivision.
  MeshDesc m;
  m.name = "octahedron";
  m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  return loop_subdivide(m, levels + 6);
}

// The shared scenes folder: $KILN_SHARED_DIR, else the default checkout layout (../shared next to the sources).
std::string shared_dir() {
  if (const char* env = std::getenv("KILN_SHARED_DIR")) return env;
#ifdef KILN_SHARED_DIR
  return KILN_SHARED_DIR;
#else
  return std::string(KILN_BUNDLED_SCENES_DIR) + "/../../shared";
#endif
}

MeshDesc base_mesh() {
  const std::string path = shared_dir() + "/scenes/killeroo/killeroo.ply";
  if (std::filesystem::exists(path)) return load_ply(path);
  return icosphere_desc(0);
}

struct Fixture {
  WorldGeometry g;
  std::unique_ptr<EmbreeAccel> embree;
  std::unique_ptr<Bvh> bvh;
  std::vector<Ray> primary, bounce, shadow;

  explicit Fixture(int levels) {
    const MeshDesc base = base_mesh();
    const MeshDesc m = levels > 0 ? loop_subdivide(base, levels) : base;
    TriangleMesh tm;
    for (const Vec3f& p : m.positions) tm.p.push_back(m.to_world.point(p));
    tm.idx = m.indices;
    g.meshes.push_back(std::move(tm));
    g.shapes.push_back({ShapeKind::Mesh, 0});
    embree = std::make_unique<EmbreeAccel>(g);
    bvh = std::make_unique<Bvh>(g);

    // A camera framing the mesh from a diagonal, a point light above it.
    const Bounds3f b = geometry_bounds(g);
    const float ext = b.extent();
    const Vec3f eye = b.center() + normalize(Vec3f(0.6f, 0.5f, 1.0f)) * (kCameraDistance * ext);
    const Vec3f light = b.center() + Vec3f(0.3f, 1.0f, 0.2f) * ext;
    const Frame cam(normalize(b.center() - eye));
    Rng rng(1, 0);
    for (int y = 0; y < kImageSide; ++y)
      for (int x = 0; x < kImageSide; ++x) {
        const Vec3f local((float(x) + 0.5f) / kImageSide - 0.5f, (float(y) + 0.5f) / kImageSide - 0.5f, 1.0f);
        const Ray r{eye, cam.to_world(local)};
        primary.push_back(r);
        Hit h;
        if (!embree->intersect(r, h)) continue;
        const Vec3f p = surface_point(g, r, h).p;
        const Vec3f ng = normalize(h.ng);
        const Frame f(face_forward(ng, -r.d));
        bounce.push_back(spawn_ray(p, ng, f.to_world(sample_cosine_hemisphere(rng.next_2d()))));
        shadow.push_back(spawn_ray_to(p, ng, light));
      }
  }
  const std::vector<Ray>& rays(int kind) const { return kind == 0 ? primary : kind == 1 ? bounce : shadow; }
  const Accelerator& accel(bool use_bvh) const {
    return use_bvh ? static_cast<const Accelerator&>(*bvh) : static_cast<const Accelerator&>(*embree);
  }
};

const Fixture& fixture(int levels) {
  static std::mutex mu;
  static std::map<int, std::unique_ptr<Fixture>> cache;
  const std::lock_guard lock(mu);
  auto& f = cache[levels];
  if (!f) f = std::make_unique<Fixture>(levels);
  return *f;
}

// CPU seconds used by all threads of the process so far: on a shared machine the wall clock of a parallel build
// mostly measures the other load, so builds also report triangles per CPU-second.
double process_cpu_seconds() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

template <bool kBvh>
void BM_AccelBuild(benchmark::State& state) {
  const Fixture& f = fixture(int(state.range(0)));
  double seconds = 0;
  size_t bytes = 0;
  const double cpu0 = process_cpu_seconds();
  for (auto _ : state) {
    if constexpr (kBvh) {
      const Bvh acc(f.g);
      seconds += acc.stats().build_seconds;
      bytes = acc.stats().bytes;
    } else {
      const EmbreeAccel acc(f.g);
      seconds += acc.stats().build_seconds;
      bytes = acc.stats().bytes;
    }
  }
  state.counters["MB"] = double(bytes) * 1e-6;
  const double tris = double(f.g.meshes[0].triangle_count());
  state.counters["triangles"] = tris;
  state.counters["Mtris/s"] = tris * double(state.iterations()) / seconds * 1e-6;
  state.counters["Mtris/cpu-s"] = tris * double(state.iterations()) / (process_cpu_seconds() - cpu0) * 1e-6;
}

// kind: 0 primary (coherent), 1 diffuse bounce (incoherent), 2 shadow (occlusion).
template <bool kBvh>
void BM_AccelTrace(benchmark::State& state) {
  const Fixture& f = fixture(int(state.range(0)));
  const int kind = int(state.range(1));
  trace_rays_benchmark(state, f.accel(kBvh), f.rays(kind), kind);
}

void trace_args(benchmark::internal::Benchmark* b) {
  for (int level : {0, 1, 2, 3, 4})
    for (int kind : {0, 1, 2}) b->Args({level, kind});
}

BENCHMARK(BM_AccelBuild<false>)
    ->Name("AccelBuild/embree")
    ->DenseRange(0, 4)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_AccelBuild<true>)->Name("AccelBuild/bvh")->DenseRange(0, 4)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AccelTrace<false>)->Name("AccelTrace/embree")->Apply(trace_args)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AccelTrace<true>)->Name("AccelTrace/bvh")->Apply(trace_args)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace kiln

BENCHMARK_MAIN();
