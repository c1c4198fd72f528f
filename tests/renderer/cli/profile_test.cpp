// `kiln profile`: a smoke run on a tiny generated PLY (JSON keys and consistency of the numbers), the table, the
// scene's own subdivision level on the bundled killeroo scene, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "renderer/cli/profile.h"

namespace kiln {
namespace {

// An octahedron (8 triangles) as ASCII PLY; the quick-look scene adds a 2-triangle ground plane.
std::string tiny_ply() {
  const std::filesystem::path dir = std::filesystem::path(KILN_TEST_TMP) / "profile";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "octahedron.ply").string();
  std::ofstream f(path);
  f << "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 8\nproperty list uchar int vertex_indices\nend_header\n"
       "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
       "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";
  return path;
}

constexpr size_t kTinyTriangles = 8 + 2;

ProfileArgs tiny_args() {
  ProfileArgs a;
  a.scene = tiny_ply();
  a.subdivide = 2;
  a.spp = 1;
  return a;
}

TEST(Profile, ReportIsConsistent) {
  const ProfileReport r = run_profile(tiny_args());
  EXPECT_EQ(r.triangles, kTinyTriangles * 16);
  EXPECT_EQ(r.meshes, 2u);
  EXPECT_EQ(r.accel, "embree");
  EXPECT_TRUE(r.rendered);
  EXPECT_EQ(r.primary.count, uint64_t(r.width) * uint64_t(r.height));
  EXPECT_EQ(r.total.count, r.primary.count + r.shadow.count + r.indirect.count);
  EXPECT_GT(r.shadow.count, 0u);  // the quick-look scene has an area light
  EXPECT_GT(r.total.mrays_per_second, 0.0);
  EXPECT_GT(r.mrays_per_cpu_second, 0.0);
  EXPECT_NEAR(r.total.mrays_per_second,
              r.primary.mrays_per_second + r.shadow.mrays_per_second + r.indirect.mrays_per_second, 1e-9);
  EXPECT_GT(r.ray_query_share, 0.0);
  EXPECT_LE(r.ray_query_share, 1.0);
  for (double s :
       {r.parse_seconds, r.subdivision_seconds, r.world_build_seconds, r.accel_build_seconds, r.render_seconds})
    EXPECT_GE(s, 0.0);
  EXPECT_GE(r.total_seconds, r.load_subdivision_build_seconds());
  EXPECT_GT(r.render_cpu_seconds, 0.0);
  EXPECT_GT(r.peak_rss, 0u);
  EXPECT_GE(r.peak_rss, r.build_peak_rss);
  EXPECT_GT(r.bytes_per_triangle(), 0.0);
  // 160 triangles, 82 + 9 vertices: positions and indices as described, once in the world, normals for both.
  EXPECT_GE(r.scene_desc_bytes, r.triangles * 3 * sizeof(uint32_t));
  EXPECT_GE(r.world_geometry_bytes, r.triangles * 3 * sizeof(uint32_t));
  EXPECT_GT(r.world_normals_bytes, 0u);
}

TEST(Profile, JsonHasEveryKey) {
  ProfileArgs a = tiny_args();
  a.json = true;
  testing::internal::CaptureStdout();
  const int code = cmd_profile(a);
  const std::string out = testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  const nlohmann::json j = nlohmann::json::parse(out);
  for (const char* k : {"scene", "subdivide", "accel", "threads", "meshes", "triangles", "phases", "cpu_seconds",
                        "load_average", "render", "rays", "time_share", "memory"})
    EXPECT_TRUE(j.contains(k)) << k;
  for (const char* k : {"parse_seconds", "subdivision_seconds", "world_build_seconds", "accel_build_seconds",
                        "load_subdivision_build_seconds", "render_seconds", "total_seconds"})
    EXPECT_TRUE(j["phases"][k].is_number()) << k;
  for (const char* k : {"parse", "subdivision", "world_and_accel_build", "render"})
    EXPECT_GE(j["cpu_seconds"][k].get<double>(), 0.0) << k;
  for (const char* kind : {"primary", "shadow", "indirect", "total"}) {
    EXPECT_TRUE(j["rays"][kind]["count"].is_number_unsigned()) << kind;
    EXPECT_TRUE(j["rays"][kind]["mrays_per_second"].is_number()) << kind;
  }
  EXPECT_GT(j["rays"]["mrays_per_cpu_second"].get<double>(), 0.0);
  EXPECT_NEAR(j["time_share"]["ray_queries"].get<double>() + j["time_share"]["shading_and_sampling"].get<double>(),
              1.0, 1e-12);
  for (const char* k : {"peak_rss_bytes", "baseline_rss_bytes", "bytes_per_triangle", "net_bytes_per_triangle",
                        "peak_source", "phase_peak_rss_bytes", "scene_desc_bytes", "world_geometry_bytes",
                        "world_normals_bytes", "accel_bytes"})
    EXPECT_TRUE(j["memory"].contains(k)) << k;
  EXPECT_EQ(j["triangles"].get<size_t>(), kTinyTriangles * 16);
  EXPECT_EQ(j["subdivide"].get<int>(), 2);
  EXPECT_GT(j["memory"]["peak_rss_bytes"].get<size_t>(), 0u);
}

TEST(Profile, TableNamesEveryPhase) {
  ProfileArgs a = tiny_args();
  a.no_render = true;
  const ProfileReport r = run_profile(a);
  EXPECT_FALSE(r.rendered);
  EXPECT_EQ(r.primary.count, 0u);
  const std::string t = profile_table(r);
  for (const char* k : {"parse", "subdivision", "world build", "accelerator build", "load+subdivision+build",
                        "peak RSS", "B/triangle", "scene description", "accelerator"})
    EXPECT_NE(t.find(k), std::string::npos) << k << "\n" << t;
  EXPECT_EQ(t.find("Mrays/s"), std::string::npos);  // nothing rendered
}

TEST(Profile, BvhAccelerator) {
  ProfileArgs a = tiny_args();
  a.accel = AccelKind::Bvh;
  const ProfileReport r = run_profile(a);
  EXPECT_NE(r.accel, "embree");
  EXPECT_EQ(r.primary.count, uint64_t(r.width) * uint64_t(r.height));
}

TEST(Profile, BundledKillerooKeepsTheScenesLevelOrOverridesIt) {
  const std::string scene = std::string(KILN_SOURCE_DIR) + "/scenes/killeroo_blinnphong.xml";
  ProfileArgs a;
  a.scene = scene;
  a.no_render = true;
  a.subdivide = 0;
  const ProfileReport cage = run_profile(a);
  EXPECT_EQ(cage.triangles, 8316u + 6u);  // killeroo + floor and two walls
  // --subdivide overrides the level of the meshes the scene marks (the killeroo), not the floor and walls.
  a.subdivide = 1;
  EXPECT_EQ(run_profile(a).triangles, 8316u * 4 + 6u);
  a.subdivide = -1;  // the scene's own level (subdivide="2" on the killeroo)
  EXPECT_EQ(run_profile(a).triangles, 8316u * 16 + 6u);
}

TEST(Profile, BadInputIsAnError) {
  ProfileArgs a;
  a.scene = std::string(KILN_TEST_TMP) + "/profile/missing.ply";
  EXPECT_THROW(run_profile(a), Error);
  a = tiny_args();
  a.camera = "no-such-camera";
  EXPECT_THROW(run_profile(a), Error);
}

}  // namespace
}  // namespace kiln
