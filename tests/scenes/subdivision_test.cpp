// Loop subdivision: counts (T' = 4T, V' = V + E), closed meshes stay closed and consistently wound, convergence
// to a round limit, Loop's weights on hand-computed valence-3 and valence-6 examples, boundary (curve) rules on
// planar patches, limit normals (the same limit point keeps its normal across levels and matches the fine mesh),
// non-manifold input, thread-count independence, and errors. The bundled killeroo scenes load.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <string>
#include <utility>

#include "core/error.h"
#include "scenes/loader.h"
#include "scenes/ply_loader.h"
#include "scenes/subdivision.h"

namespace kiln {
namespace {

MeshDesc make_mesh(std::vector<Vec3f> p, std::vector<uint32_t> idx, const std::string& name = "test mesh") {
  MeshDesc m;
  m.name = name;
  m.positions = std::move(p);
  m.indices = std::move(idx);
  return m;
}

MeshDesc tetrahedron() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});
}

// Unit icosahedron; faces found as the vertex triples at edge distance, wound outwards.
MeshDesc icosahedron() {
  const float phi = 0.5f * (1.0f + std::sqrt(5.0f));
  std::vector<Vec3f> p;
  for (float s : {-1.0f, 1.0f})
    for (float t : {-phi, phi}) {
      p.push_back({0, s, t});
      p.push_back({s, t, 0});
      p.push_back({t, 0, s});
    }
  std::vector<uint32_t> idx;
  auto is_edge = [&](uint32_t a, uint32_t b) { return std::abs(length(p[a] - p[b]) - 2.0f) < 1e-4f; };
  for (uint32_t a = 0; a < 12; ++a)
    for (uint32_t b = a + 1; b < 12; ++b)
      for (uint32_t c = b + 1; c < 12; ++c)
        if (is_edge(a, b) && is_edge(b, c) && is_edge(a, c)) {
          const bool outward = dot(cross(p[b] - p[a], p[c] - p[a]), p[a] + p[b] + p[c]) > 0.0f;
          idx.insert(idx.end(), {a, outward ? b : c, outward ? c : b});
        }
  for (Vec3f& v : p) v = normalize(v);
  return make_mesh(p, idx, "icosahedron");
}

// n x n quads over [0,1]^2 in the plane z = 0, two triangles each, normal +z.
MeshDesc grid(int n) {
  std::vector<Vec3f> p;
  std::vector<uint32_t> idx;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) p.push_back({float(i) / float(n), float(j) / float(n), 0.0f});
  auto at = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      idx.insert(idx.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
  return make_mesh(p, idx, "grid");
}

// Edge -> number of adjacent faces, and directed edge -> count.
struct EdgeCounts {
  std::map<std::pair<uint32_t, uint32_t>, int> undirected, directed;
};
EdgeCounts edge_counts(const MeshDesc& m) {
  EdgeCounts e;
  for (size_t t = 0; t < m.indices.size() / 3; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.indices[3 * t + size_t(k)], b = m.indices[3 * t + size_t((k + 1) % 3)];
      ++e.undirected[{std::min(a, b), std::max(a, b)}];
      ++e.directed[{a, b}];
    }
  return e;
}

void expect_near_vec(Vec3f a, Vec3f b, float tol, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

bool contains_point(const MeshDesc& m, Vec3f q, float tol) {
  return std::any_of(m.positions.begin(), m.positions.end(), [&](Vec3f p) { return length(p - q) < tol; });
}

// Area-weighted face normal at each vertex (the fine-mesh estimate of the surface normal).
std::vector<Vec3f> face_averaged_normals(const MeshDesc& m) {
  std::vector<Vec3f> n(m.positions.size(), Vec3f(0.0f));
  for (size_t t = 0; t < m.indices.size() / 3; ++t) {
    const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
    const Vec3f fn = cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
    n[a] += fn;
    n[b] += fn;
    n[c] += fn;
  }
  for (Vec3f& v : n) v = normalize(v);
  return n;
}

TEST(LoopSubdivision, ClosedMeshCountsEulerAndClosedness) {
  for (const MeshDesc& base : {tetrahedron(), icosahedron()}) {
    MeshDesc cur = base;
    for (int level = 1; level <= 4; ++level) {
      const size_t v = cur.positions.size(), t = cur.indices.size() / 3;
      const size_t e = edge_counts(cur).undirected.size();
      MeshDesc next = loop_subdivide(cur, 1);
      ASSERT_EQ(next.indices.size() / 3, 4 * t) << base.name << " level " << level;
      ASSERT_EQ(next.positions.size(), v + e) << base.name << " level " << level;
      const EdgeCounts ec = edge_counts(next);
      for (const auto& [edge, n] : ec.undirected) ASSERT_EQ(n, 2) << base.name << " level " << level << ": open edge";
      // Consistent winding: every directed edge once, its reverse once.
      for (const auto& [edge, n] : ec.directed) ASSERT_EQ(n, 1) << base.name << " level " << level;
      // Sphere topology: V - E + F = 2.
      EXPECT_EQ(int64_t(next.positions.size()) - int64_t(ec.undirected.size()) + int64_t(next.indices.size() / 3), 2);
      EXPECT_EQ(next.normals.size(), next.positions.size());
      EXPECT_TRUE(next.smooth);
      cur = std::move(next);
    }
    // Subdividing 4 levels at once equals 4 single steps (the old vertices keep their indices).
    const MeshDesc once = loop_subdivide(base, 4);
    ASSERT_EQ(once.positions.size(), cur.positions.size());
    EXPECT_EQ(once.indices, cur.indices);
    for (size_t i = 0; i < once.positions.size(); ++i) ASSERT_EQ(once.positions[i], cur.positions[i]) << i;
  }
}

// Spread of the distances to the centre over vertices and face centroids, relative to their mean.
float radial_spread(const MeshDesc& m) {
  Vec3f c(0.0f);
  for (Vec3f p : m.positions) c += p;
  c = c / float(m.positions.size());
  std::vector<float> r;
  for (Vec3f p : m.positions) r.push_back(length(p - c));
  for (size_t t = 0; t < m.indices.size() / 3; ++t)
    r.push_back(length((m.positions[m.indices[3 * t]] + m.positions[m.indices[3 * t + 1]] +
                        m.positions[m.indices[3 * t + 2]]) / 3.0f - c));
  const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
  return (*hi - *lo) / (std::accumulate(r.begin(), r.end(), 0.0f) / float(r.size()));
}

// The icosahedron's Loop limit is round to about 3 %; the faceting (vertices vs face centroids) vanishes, so the
// spread of radii falls towards that value with geometrically shrinking steps.
TEST(LoopSubdivision, ConvergesToRoundLimitWithRadialNormals) {
  const MeshDesc ico = icosahedron();
  std::vector<float> spread{radial_spread(ico)};
  for (int level = 1; level <= 5; ++level) {
    const MeshDesc m = loop_subdivide(ico, level);
    spread.push_back(radial_spread(m));
    for (size_t i = 0; i < m.positions.size(); ++i)
      ASSERT_GT(dot(m.normals[i], normalize(m.positions[i])), 0.995f) << "level " << level << " vertex " << i;
    // The original vertices lie on symmetry axes: their limit normal is exactly radial.
    for (size_t i = 0; i < 12; ++i) expect_near_vec(m.normals[i], normalize(m.positions[i]), 1e-5f, "axis vertex");
  }
  for (size_t l = 1; l < spread.size(); ++l) EXPECT_LT(spread[l], spread[l - 1]) << "level " << l;
  for (size_t l = 2; l < spread.size(); ++l)
    EXPECT_LT(spread[l - 1] - spread[l], 0.5f * (spread[l - 2] - spread[l - 1])) << "level " << l;
  EXPECT_LT(spread.back(), 0.035f);
}

// Valence 3: the tetrahedron's corners have 3 neighbours, beta = 3/16, so v' = 7/16 v + 3/16 sum(ring);
// each edge point is 3/8 (a + b) + 1/8 (c + d).
TEST(LoopSubdivision, Valence3WeightsHandComputed) {
  const MeshDesc m = loop_subdivide(tetrahedron(), 1);
  ASSERT_EQ(m.positions.size(), 10u);
  // v0 = origin: 3/16 (e_x + e_y + e_z).
  expect_near_vec(m.positions[0], {0.1875f, 0.1875f, 0.1875f}, 1e-6f, "v0");
  // v1 = e_x: 7/16 e_x + 3/16 (0 + e_y + e_z).
  expect_near_vec(m.positions[1], {0.4375f, 0.1875f, 0.1875f}, 1e-6f, "v1");
  expect_near_vec(m.positions[3], {0.1875f, 0.1875f, 0.4375f}, 1e-6f, "v3");
  // Edge (v0, v1), opposite v2 and v3: 3/8 e_x + 1/8 (e_y + e_z).
  EXPECT_TRUE(contains_point(m, {0.375f, 0.125f, 0.125f}, 1e-6f));
  // Edge (v1, v2), opposite v0 and v3: 3/8 (e_x + e_y) + 1/8 e_z.
  EXPECT_TRUE(contains_point(m, {0.375f, 0.375f, 0.125f}, 1e-6f));
  // Edge (v0, v3), opposite v1 and v2.
  EXPECT_TRUE(contains_point(m, {0.125f, 0.125f, 0.375f}, 1e-6f));
}

// Valence 6: a hexagonal fan around c = (0,0,1) with rim r_i = (cos 60i, sin 60i, 0.1 i). c is interior with
// beta = 3/48 = 1/16: c' = 10/16 c + 1/16 sum(r_i) = (0, 0, 0.625 + 1.5/16) = (0, 0, 0.71875). The rim is a
// boundary: r_0' = 6/8 r_0 + 1/8 (r_1 + r_5), rim edges split at their midpoints, and the spoke (c, r_0) with
// opposite vertices r_1, r_5 gives 3/8 (c + r_0) + 1/8 (r_1 + r_5).
TEST(LoopSubdivision, Valence6AndBoundaryWeightsHandComputed) {
  std::vector<Vec3f> p{{0, 0, 1}};
  for (int i = 0; i < 6; ++i)
    p.push_back({std::cos(radians(60.0f * float(i))), std::sin(radians(60.0f * float(i))), 0.1f * float(i)});
  std::vector<uint32_t> idx;
  for (uint32_t i = 0; i < 6; ++i) idx.insert(idx.end(), {0, 1 + i, 1 + (i + 1) % 6});
  const MeshDesc m = loop_subdivide(make_mesh(p, idx, "fan"), 1);
  ASSERT_EQ(m.positions.size(), 7u + 12u);
  expect_near_vec(m.positions[0], {0.0f, 0.0f, 0.71875f}, 1e-6f, "valence-6 centre");
  // r_0 = (1,0,0), r_1 = (0.5, 0.866025, 0.1), r_5 = (0.5, -0.866025, 0.5):
  // r_0' = (0.75 + 0.125, 0, 0.075) = (0.875, 0, 0.075).
  expect_near_vec(m.positions[1], {0.875f, 0.0f, 0.075f}, 1e-6f, "boundary r0");
  // Rim edge (r_0, r_1) midpoint: (0.75, 0.4330127, 0.05).
  EXPECT_TRUE(contains_point(m, {0.75f, 0.4330127f, 0.05f}, 1e-6f));
  // Spoke (c, r_0): 3/8 (1, 0, 1) + 1/8 (1, 0, 0.6) = (0.5, 0, 0.45).
  EXPECT_TRUE(contains_point(m, {0.5f, 0.0f, 0.45f}, 1e-6f));
}

TEST(LoopSubdivision, SingleTriangleFollowsCurveRuleAndStaysPlanar) {
  const MeshDesc tri = make_mesh({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}, {0, 1, 2}, "triangle");
  const MeshDesc m = loop_subdivide(tri, 1);
  ASSERT_EQ(m.positions.size(), 6u);
  ASSERT_EQ(m.indices.size(), 12u);
  // Every vertex is a boundary vertex on two boundary edges: 6/8 v + 1/8 (both neighbours).
  expect_near_vec(m.positions[0], {0.5f, 0.5f, 0.0f}, 1e-6f, "v0");
  expect_near_vec(m.positions[1], {3.0f, 0.5f, 0.0f}, 1e-6f, "v1");
  expect_near_vec(m.positions[2], {0.5f, 3.0f, 0.0f}, 1e-6f, "v2");
  // Boundary edges split at their midpoints.
  for (Vec3f mid : {Vec3f(2, 0, 0), Vec3f(2, 2, 0), Vec3f(0, 2, 0)}) EXPECT_TRUE(contains_point(m, mid, 1e-6f));
  const MeshDesc deep = loop_subdivide(tri, 4);
  for (size_t i = 0; i < deep.positions.size(); ++i) {
    ASSERT_EQ(deep.positions[i].z, 0.0f) << i;
    expect_near_vec(deep.normals[i], {0, 0, 1}, 1e-6f, "planar limit normal");
  }
}

TEST(LoopSubdivision, PlanarPatchBoundaryMovesOnlyAlongItsLine) {
  const MeshDesc patch = grid(4);
  for (int level = 1; level <= 3; ++level) {
    const MeshDesc m = loop_subdivide(patch, level);
    ASSERT_EQ(m.indices.size() / 3, 32u << (2 * level));
    for (size_t i = 0; i < m.positions.size(); ++i) {
      ASSERT_EQ(m.positions[i].z, 0.0f) << "level " << level << " vertex " << i;
      expect_near_vec(m.normals[i], {0, 0, 1}, 1e-6f, "planar limit normal");
    }
    // Boundary vertices (on edges with one face), away from the 4 corners (which the curve rule rounds off:
    // corner (0,0) goes to (1/32, 1/32) at level 1), stay exactly on the square's sides.
    size_t checked = 0;
    for (const auto& [edge, n] : edge_counts(m).undirected) {
      if (n != 1) continue;
      for (uint32_t v : {edge.first, edge.second}) {
        const Vec3f q = m.positions[v];
        const float along_x = std::min(q.x, 1.0f - q.x), along_y = std::min(q.y, 1.0f - q.y);
        if (std::min(along_x, along_y) > 0.1f) ADD_FAILURE() << "boundary vertex left the boundary";
        if (std::max(along_x, along_y) < 0.3f) continue;  // within a corner's reach
        ASSERT_EQ(std::min(along_x, along_y), 0.0f) << "level " << level << " (" << q.x << ", " << q.y << ")";
        ++checked;
      }
    }
    EXPECT_GT(checked, 0u);
    if (level == 1) {
      expect_near_vec(m.positions[0], {1.0f / 32.0f, 1.0f / 32.0f, 0.0f}, 1e-6f, "corner (0,0)");
      // Interior grid vertex (1/4, 1/4), valence 6: 10/16 v + 1/16 sum(ring); the ring's centroid is v, so v stays.
      expect_near_vec(m.positions[6], {0.25f, 0.25f, 0.0f}, 1e-6f, "interior vertex");
    }
  }
}

// The limit point of a vertex is the same at every level, so its limit normal is too; at a fine level it agrees
// with the face-averaged normal. Checked on a lumpy closed mesh and on an open cap with boundary vertices of
// valence 2 to 5.
TEST(LoopSubdivision, LimitNormalsAreLevelIndependentAndMatchFineSurface) {
  MeshDesc lumpy = icosahedron();
  for (size_t i = 0; i < lumpy.positions.size(); ++i) lumpy.positions[i] *= 1.0f + 0.3f * std::sin(float(7 * i + 1));
  // Open cap: the icosahedron without the 5 faces around vertex 0 and one more face (boundary valences vary).
  MeshDesc cap = icosahedron();
  std::vector<uint32_t> kept;
  bool dropped_extra = false;
  for (size_t t = 0; t < cap.indices.size() / 3; ++t) {
    const uint32_t* f = &cap.indices[3 * t];
    const bool touches0 = f[0] == 0 || f[1] == 0 || f[2] == 0;
    const bool touches_ring = std::abs(dot(cap.positions[f[0]], cap.positions[0]) - 0.4472136f) < 1e-3f;
    if (touches0) continue;
    if (!dropped_extra && touches_ring) {
      dropped_extra = true;
      continue;
    }
    kept.insert(kept.end(), f, f + 3);
  }
  cap.indices = kept;
  cap.name = "cap";
  for (const MeshDesc& base : {lumpy, cap}) {
    const MeshDesc l1 = loop_subdivide(base, 1), l3 = loop_subdivide(base, 3), l6 = loop_subdivide(base, 6);
    const std::vector<Vec3f> fine = face_averaged_normals(l6);
    for (size_t i = 0; i < l1.positions.size(); ++i) {
      if (base.name == "cap" && i == 0) continue;  // unreferenced vertex
      expect_near_vec(l1.normals[i], l3.normals[i], 2e-5f, base.name + " vertex " + std::to_string(i));
      EXPECT_GT(dot(l1.normals[i], fine[i]), 0.9995f) << base.name << " vertex " << i;
    }
  }
}

TEST(LoopSubdivision, NonManifoldAndDegenerateInputDoesNotCrash) {
  // Three fins on the edge (0,0,0)-(1,0,0), a bowtie at vertex 0, a degenerate triangle and an unused vertex.
  const MeshDesc m = make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}, {-1, 0.5f, 0},
                                {-1, -0.5f, 0}, {7, 7, 7}},
                               {0, 1, 2, 1, 0, 3, 0, 1, 4, 0, 5, 6, 2, 2, 4});
  for (int level = 1; level <= 3; ++level) {
    const MeshDesc s = loop_subdivide(m, level);
    ASSERT_EQ(s.indices.size(), m.indices.size() << (2 * level));
    for (Vec3f p : s.positions) ASSERT_TRUE(is_finite(p));
    for (Vec3f n : s.normals) {
      ASSERT_TRUE(is_finite(n));
      const float l = length(n);
      ASSERT_TRUE(l == 0.0f || std::abs(l - 1.0f) < 1e-5f);
    }
  }
  const MeshDesc s = loop_subdivide(m, 1);
  // The 3-face edge is a crease: split at its midpoint. Vertex 0 ends 6 crease edges (a corner) and stays.
  EXPECT_TRUE(contains_point(s, {0.5f, 0, 0}, 1e-6f));
  EXPECT_EQ(s.positions[0], m.positions[0]);
  EXPECT_EQ(s.positions[7], m.positions[7]);
}

TEST(LoopSubdivision, ResultDoesNotDependOnThreadCount) {
  MeshDesc lumpy = icosahedron();
  for (size_t i = 0; i < lumpy.positions.size(); ++i) lumpy.positions[i] *= 1.0f + 0.2f * std::cos(float(3 * i));
  const MeshDesc many = loop_subdivide(lumpy, 5);
  MeshDesc one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = loop_subdivide(lumpy, 5);
  }
  EXPECT_EQ(one.indices, many.indices);
  ASSERT_EQ(one.positions.size(), many.positions.size());
  for (size_t i = 0; i < one.positions.size(); ++i) {
    ASSERT_EQ(one.positions[i], many.positions[i]) << i;
    ASSERT_EQ(one.normals[i], many.normals[i]) << i;
  }
}

TEST(LoopSubdivision, CarriesUvsAndMetadata) {
  MeshDesc m = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, "uv triangle");
  m.uvs = {{0, 0}, {1, 0}, {0, 1}};
  m.material = 3;
  m.emission = Rgb(2.0f);
  m.subdivide = 2;
  const MeshDesc s = loop_subdivide(m, 2);
  ASSERT_EQ(s.uvs.size(), s.positions.size());
  EXPECT_EQ(s.name, "uv triangle");
  EXPECT_EQ(s.material, 3);
  ASSERT_TRUE(s.emission);
  EXPECT_EQ(s.subdivide, 0);
  for (Vec2f uv : s.uvs) EXPECT_LE(uv.x + uv.y, 1.0f + 1e-6f);
  EXPECT_EQ(loop_subdivide(m, 0).positions, m.positions);
}

TEST(LoopSubdivision, BadInputIsAnErrorNamingTheMesh) {
  const MeshDesc bad = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 5}, "Mesh id=9");
  try {
    loop_subdivide(bad, 1);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Mesh id=9"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loop_subdivide(tetrahedron(), 16), Error);  // 4^16 * 4 triangles
}

TEST(LoopSubdivision, ApplySubdivisionAndLoadOption) {
  SceneDesc scene;
  scene.meshes = {tetrahedron(), icosahedron()};
  scene.meshes[0].subdivide = 2;
  apply_subdivision(scene);
  EXPECT_EQ(scene.meshes[0].indices.size() / 3, 64u);
  EXPECT_EQ(scene.meshes[0].subdivide, 0);
  EXPECT_EQ(scene.meshes[1].indices.size() / 3, 20u);

  const std::string cube = std::string(KILN_SOURCE_DIR) + "/tests/data/ply/cube_quads.ply";
  const size_t base = load_ply(cube).indices.size() / 3;
  LoadOptions lo;
  lo.subdivide = 2;
  const SceneDesc s = load_scene(cube, lo);
  EXPECT_EQ(s.meshes[0].indices.size() / 3, base * 16);
}

TEST(LoopSubdivision, KillerooCageCounts) {
  const std::string path = std::string(KILN_SOURCE_DIR) + "/scenes/killeroo/killeroo.ply";
  const MeshDesc cage = load_ply(path);
  ASSERT_EQ(cage.indices.size() / 3, 8316u);
  size_t expected = 8316;
  for (int level = 1; level <= 3; ++level) {
    expected *= 4;
    const MeshDesc m = loop_subdivide(cage, level);
    EXPECT_EQ(m.indices.size() / 3, expected) << "level " << level;
    for (Vec3f n : m.normals) ASSERT_NEAR(length(n), 1.0f, 1e-5f);
  }
}

TEST(BundledScenes, KillerooScenesLoad) {
  for (const char* name : {"killeroo_blinnphong.xml", "killeroo_torrancesparrow.xml", "killeroo_path.xml"}) {
    const std::string path = std::string(KILN_SOURCE_DIR) + "/scenes/" + name;
    SCOPED_TRACE(path);
    const SceneDesc s = load_scene(path);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_TRUE(s.unsupported.empty());
    ASSERT_FALSE(s.cameras.empty());
    size_t triangles = 0;
    for (const MeshDesc& m : s.meshes) triangles += m.indices.size() / 3;
    EXPECT_GE(triangles, 8316u);
  }
}

}  // namespace
}  // namespace kiln
