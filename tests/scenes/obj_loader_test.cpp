// OBJ loading through tinyobjloader: triangulation, relative indices, normals and winding, de-duplication, and
// errors naming the file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scenes/obj_loader.h"
#include "support/shared_data.h"

namespace kiln {
namespace {

const std::string kObjData = std::string(KILN_SOURCE_DIR) + "/tests/data/obj/";

Vec3f corner(const MeshDesc& m, size_t tri, int k) { return m.positions[m.indices[3 * tri + k]]; }
Vec3f geometric_normal(const MeshDesc& m, size_t tri) {
  return cross(corner(m, tri, 1) - corner(m, tri, 0), corner(m, tri, 2) - corner(m, tri, 0));
}
size_t triangle_count(const MeshDesc& m) { return m.indices.size() / 3; }
float total_area(const MeshDesc& m) {
  float a = 0;
  for (size_t t = 0; t < triangle_count(m); ++t) a += 0.5f * length(geometric_normal(m, t));
  return a;
}

// Runs f, expects a kiln::Error, returns its message.
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no kiln::Error thrown";
  return {};
}

TEST(ObjLoader, QuadWithoutNormalsIsTwoTrianglesKeepingWinding) {
  const MeshDesc m = load_obj(kObjData + "quad_no_normals.obj");
  EXPECT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(triangle_count(m), 2u);
  EXPECT_TRUE(m.normals.empty());
  EXPECT_TRUE(m.uvs.empty());
  EXPECT_FLOAT_EQ(total_area(m), 1.0f);
  for (size_t t = 0; t < 2; ++t) EXPECT_GT(geometric_normal(m, t).z, 0.0f) << "triangle " << t;
  EXPECT_EQ(m.name, kObjData + "quad_no_normals.obj");
}

TEST(ObjLoader, NegativeIndicesMatchPositiveOnes) {
  const MeshDesc pos = load_obj(kObjData + "quad_no_normals.obj");
  const MeshDesc neg = load_obj(kObjData + "quad_negative_indices.obj");
  EXPECT_EQ(neg.positions, pos.positions);
  EXPECT_EQ(neg.indices, pos.indices);
}

TEST(ObjLoader, NegativeIndicesAreRelativeToTheFaceLine) {
  const MeshDesc m = load_obj(kObjData + "two_quads_relative.obj");
  ASSERT_EQ(triangle_count(m), 4u);
  ASSERT_EQ(m.positions.size(), 8u);  // the two faces name different vertices
  ASSERT_EQ(m.normals.size(), 8u);
  float z_sum = 0;
  for (size_t t = 0; t < 4; ++t)
    for (int k = 0; k < 3; ++k) z_sum += corner(m, t, k).z;
  EXPECT_FLOAT_EQ(z_sum, 6 * 5.0f);  // 2 triangles x 3 corners at z = 5
  for (const Vec3f& n : m.normals) EXPECT_EQ(n, Vec3f(0, 0, 1));
}

TEST(ObjLoader, ConcavePolygonIsTriangulatedWithItsAreaAndWinding) {
  const MeshDesc m = load_obj(kObjData + "concave_polygon.obj");
  EXPECT_EQ(m.positions.size(), 5u);
  EXPECT_GE(triangle_count(m), 3u);
  EXPECT_FLOAT_EQ(total_area(m), 3.0f);  // a fan from vertex 1 would cover area 4 (it crosses the notch)
  for (size_t t = 0; t < triangle_count(m); ++t) EXPECT_GE(geometric_normal(m, t).z, 0.0f) << "triangle " << t;
}

TEST(ObjLoader, WindingIsFlippedToAgreeWithVertexNormals) {
  const MeshDesc m = load_obj(kObjData + "winding_against_normals.obj");
  ASSERT_EQ(triangle_count(m), 2u);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  for (size_t t = 0; t < 2; ++t) {
    const Vec3f ng = geometric_normal(m, t);
    EXPECT_GT(ng.y, 0.0f) << "triangle " << t;
    EXPECT_FLOAT_EQ(length(ng), 1.0f);  // flipping keeps the triangle
  }
  // The uvs still belong to their positions after the flip (vt i was written next to v i in the file).
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_EQ(m.uvs[i].x, m.positions[i].x);
    EXPECT_EQ(m.uvs[i].y, m.positions[i].z);
  }
}

TEST(ObjLoader, VerticesAreDeduplicatedByIndexTriple) {
  const MeshDesc m = load_obj(kObjData + "cube_flat_normals.obj");
  EXPECT_EQ(triangle_count(m), 12u);
  EXPECT_EQ(m.positions.size(), 24u);
  EXPECT_FLOAT_EQ(total_area(m), 6.0f);
  for (size_t t = 0; t < 12; ++t) {
    const Vec3f ng = normalize(geometric_normal(m, t));
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(dot(ng, m.normals[m.indices[3 * t + k]]), 1.0f) << t;
  }
  // Without vn the 8 corners are shared.
  const MeshDesc shared = parse_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n",
      "cube.obj");
  EXPECT_EQ(shared.positions.size(), 8u);
  EXPECT_EQ(triangle_count(shared), 12u);
}

TEST(ObjLoader, NormalsAreDroppedWhenSomeFaceVerticesLackThem) {
  const MeshDesc m = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n", "mixed");
  EXPECT_EQ(triangle_count(m), 2u);
  EXPECT_TRUE(m.normals.empty());
  EXPECT_EQ(m.positions.size(), 4u);
}

TEST(ObjLoader, AcceptsCrlfTabsCommentsGroupsAndForwardReferences) {
  const MeshDesc m = parse_obj(
      "# comment\r\nmtllib none.mtl\r\no a\r\nf 1 2 3\r\ng b\r\nv\t0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\n"
      "usemtl x\r\ns 1\r\nf 1 2 3\r\n",
      "crlf.obj");
  EXPECT_EQ(triangle_count(m), 2u);
  EXPECT_EQ(m.positions.size(), 3u);
}

TEST(ObjLoader, OutOfRangeIndexIsAnErrorNamingTheLine) {
  const std::string msg = error_of([] { load_obj(kObjData + "out_of_range_index.obj"); });
  EXPECT_NE(msg.find("out_of_range_index.obj: line 6:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("index 9 is out of range"), std::string::npos) << msg;
}

TEST(ObjLoader, ZeroIndexIsAnErrorNamingTheLine) {
  const std::string msg = error_of([] { load_obj(kObjData + "zero_index.obj"); });
  EXPECT_NE(msg.find("zero_index.obj: line 6:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("index 0"), std::string::npos) << msg;
}

TEST(ObjLoader, BadIndicesOfEveryKindAreErrors) {
  struct Case {
    const char* text;
    const char* expected;
  } cases[] = {
      {"v 0 0 0\nv 1 0 0\nf 1 2 -3\nv 0 1 0\n", "line 3: relative face vertex index -3 is out of range"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", "line 5: face normal index 2 is out of range"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n", "line 4: face texture coordinate index 1 is out of range"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2.5 3\n", "line 4: face index '2.5' is not an integer"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/\n", "line 4: face index '' is not an integer"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", "line 4: face vertex '1/1/1/1' has more than three"},
      {"v 0 0 0\nv 1 0 0\nf 1 2\n", "line 3: face 'f' needs at least 3 vertices, got 2"},
      // Lines end in \r\n, a lone \r or \n, as tinyobjloader reads them: the blank fourth line is \r\n.
      {"v 0 0 0\r\nv 1 0 0\rv 0 1 0\n\r\nf 1 2 4\n",
       "line 5: face vertex index 4 is out of range (the file defines 3 vertices)"},
      {"v 0 0 0\nv 1 x 0\n", "line 2: vertex position 'v': 'x' is not a finite number"},
      {"v 0 0\n", "line 1: vertex position 'v' needs 3 to 6 numbers, got 2"},
      {"vn 0 0 nan\n", "line 1: vertex normal 'vn': 'nan' is not a finite number"},
      {"v 0 0 0\n# no faces\n", "the OBJ file has no faces"},
      {"", "the OBJ file has no faces"},
  };
  for (const Case& c : cases) {
    const std::string msg = error_of([&] { parse_obj(c.text, "bad.obj"); });
    EXPECT_NE(msg.find(std::string("bad.obj: ") + c.expected), std::string::npos)
        << "input:\n" << c.text << "message: " << msg;
  }
}

TEST(ObjLoader, MissingFileIsAnErrorNamingIt) {
  const std::string path = kObjData + "does_not_exist.obj";
  const std::string msg = error_of([&] { load_obj(path); });
  EXPECT_EQ(msg, path + ": OBJ file does not exist");
  EXPECT_NE(error_of([] { load_obj(kObjData); }).find("not a regular file"), std::string::npos);
}

class Cs171Assets : public ::testing::Test {
 protected:
  void SetUp() override {
    KILN_NEED_SHARED_PATH(dir_);
  }
  const std::string dir_ = std::string(KILN_SHARED_DIR) + "/scenes/cs171/assets/";
};

// The walls' winding disagrees with their inward vn; after loading, geometric normals point into the room.
TEST_F(Cs171Assets, WallsFaceIntoTheRoom) {
  const struct {
    const char* file;
    Vec3f inward;
  } walls[] = {{"floor.obj", {0, 1, 0}}, {"ceiling.obj", {0, -1, 0}}, {"back.obj", {0, 0, 1}},
               {"left.obj", {1, 0, 0}},  {"right.obj", {-1, 0, 0}}};
  for (const auto& w : walls) {
    const MeshDesc m = load_obj(dir_ + w.file);
    ASSERT_EQ(triangle_count(m), 2u) << w.file;
    ASSERT_FALSE(m.normals.empty()) << w.file;
    for (size_t t = 0; t < 2; ++t) EXPECT_GT(dot(geometric_normal(m, t), w.inward), 0.0f) << w.file;
  }
}

TEST_F(Cs171Assets, BunnyCountsAndBounds) {
  const MeshDesc m = load_obj(dir_ + "stanford_bunny.obj");
  EXPECT_EQ(triangle_count(m), 7361u);
  EXPECT_EQ(m.positions.size(), 3716u);
  EXPECT_EQ(m.normals.size(), 3716u);
  Vec3f lo(kInfinity), hi(-kInfinity);
  for (const Vec3f& p : m.positions) lo = min(lo, p), hi = max(hi, p);
  EXPECT_NEAR(lo.y, 0.0331f, 1e-4f);
  EXPECT_NEAR(hi.y, 0.1870f, 1e-4f);
  for (size_t t = 0; t < triangle_count(m); ++t) {
    const Vec3f ns = m.normals[m.indices[3 * t]] + m.normals[m.indices[3 * t + 1]] + m.normals[m.indices[3 * t + 2]];
    ASSERT_GE(dot(geometric_normal(m, t), ns), 0.0f) << "triangle " << t;
  }
}

TEST_F(Cs171Assets, BoxesAreClosedAndOutwardFacing) {
  for (const char* file : {"short_box.obj", "tall_box.obj"}) {
    const MeshDesc m = load_obj(dir_ + file);
    ASSERT_EQ(triangle_count(m), 12u) << file;
    // Divergence theorem: for a closed outward-oriented surface, sum over triangles of (centroid . n) A / 3 = V > 0.
    double volume = 0;
    for (size_t t = 0; t < 12; ++t) {
      const Vec3f c = (corner(m, t, 0) + corner(m, t, 1) + corner(m, t, 2)) / 3.0f;
      volume += dot(c, geometric_normal(m, t)) / 6.0;
    }
    EXPECT_GT(volume, 0.0) << file;
  }
}

}  // namespace
}  // namespace kiln
