// PLY loading: ASCII polygons triangulated as fans, binary little/big endian round trips over every scalar type,
// skipped elements/properties, the fast and generic face paths agreeing, and validation (truncation at every
// byte, bad indices, short faces, bad headers, non-finite values) as kiln::Error naming the file.
#include "scenes/ply_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace kiln {
namespace {

const std::string kPlyData = std::string(KILN_SOURCE_DIR) + "/tests/data/ply/";

std::string tmp_path(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(KILN_TEST_TMP) / "ply";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

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

Vec3f corner(const MeshDesc& m, size_t tri, int k) { return m.positions[m.indices[3 * tri + size_t(k)]]; }
Vec3f geometric_normal(const MeshDesc& m, size_t tri) {
  return cross(corner(m, tri, 1) - corner(m, tri, 0), corner(m, tri, 2) - corner(m, tri, 0));
}

// Builds binary PLY bodies in either byte order.
class Bytes {
 public:
  explicit Bytes(bool big_endian) : big_(big_endian) {}
  template <typename T>
  Bytes& put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    const bool host_big = std::endian::native == std::endian::big;
    if (big_ != host_big) std::reverse(b, b + sizeof(T));
    s_.append(b, sizeof(T));
    return *this;
  }
  const std::string& str() const { return s_; }

 private:
  bool big_;
  std::string s_;
};

// A small mesh with normals and uvs: 5 vertices, one triangle and one quad.
struct Fixture {
  std::vector<Vec3f> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 2.0f}};
  std::vector<Vec3f> n{{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 1, 0}};
  std::vector<Vec2f> uv{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5f, 0.25f}};
  std::vector<std::vector<int32_t>> faces{{0, 1, 4}, {0, 1, 2, 3}};
  std::vector<uint32_t> triangulated{0, 1, 4, 0, 1, 2, 0, 2, 3};
};

std::string fixture_binary(bool big, bool extra_face_property) {
  const Fixture f;
  std::string h = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment written by the test\nelement vertex 5\nproperty float x\nproperty float y\n"
                  "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty float u\n"
                  "property float v\nelement face 2\nproperty list uchar int vertex_indices\n";
  if (extra_face_property) h += "property int flags\n";
  h += "end_header\n";
  Bytes b(big);
  for (size_t i = 0; i < 5; ++i)
    b.put(f.p[i].x).put(f.p[i].y).put(f.p[i].z).put(f.n[i].x).put(f.n[i].y).put(f.n[i].z).put(f.uv[i].x).put(f.uv[i].y);
  for (const auto& face : f.faces) {
    b.put(uint8_t(face.size()));
    for (int32_t v : face) b.put(v);
    if (extra_face_property) b.put(int32_t(7));
  }
  return h + b.str();
}

void expect_fixture(const MeshDesc& m) {
  const Fixture f;
  EXPECT_EQ(m.positions, f.p);
  EXPECT_EQ(m.normals, f.n);
  ASSERT_EQ(m.uvs.size(), f.uv.size());
  for (size_t i = 0; i < f.uv.size(); ++i) {
    EXPECT_EQ(m.uvs[i].x, f.uv[i].x) << i;
    EXPECT_EQ(m.uvs[i].y, f.uv[i].y) << i;
  }
  EXPECT_EQ(m.indices, f.triangulated);
}

TEST(PlyLoader, AsciiQuadsAreTriangulatedAsFansKeepingWinding) {
  const MeshDesc m = load_ply(kPlyData + "cube_quads.ply");
  EXPECT_EQ(m.name, "cube_quads.ply");
  ASSERT_EQ(m.positions.size(), 8u);
  ASSERT_EQ(m.indices.size(), 36u);
  EXPECT_TRUE(m.normals.empty());
  EXPECT_TRUE(m.uvs.empty());
  // First quad "0 3 2 1" -> (0 3 2), (0 2 1).
  EXPECT_EQ(std::vector<uint32_t>(m.indices.begin(), m.indices.begin() + 6), (std::vector<uint32_t>{0, 3, 2, 0, 2, 1}));
  float area = 0;
  const Vec3f centre(0.5f);
  for (size_t t = 0; t < 12; ++t) {
    const Vec3f ng = geometric_normal(m, t);
    area += 0.5f * length(ng);
    const Vec3f mid = (corner(m, t, 0) + corner(m, t, 1) + corner(m, t, 2)) / 3.0f;
    EXPECT_GT(dot(ng, mid - centre), 0.0f) << "triangle " << t << " faces inwards";
  }
  EXPECT_FLOAT_EQ(area, 6.0f);
}

TEST(PlyLoader, AsciiPentagonWithCrlfDoublesAndStUv) {
  const MeshDesc m = load_ply(kPlyData + "pentagon_crlf.ply");
  ASSERT_EQ(m.positions.size(), 5u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  ASSERT_EQ(m.uvs.size(), 5u);
  EXPECT_FLOAT_EQ(m.uvs[1].x, 0.654508f);
  EXPECT_FLOAT_EQ(m.uvs[1].y, 0.975528f);
  EXPECT_FLOAT_EQ(m.positions[2].x, -0.809017f);
  // Area of a regular pentagon with circumradius 1: (5/2) sin(72 deg).
  float area = 0;
  for (size_t t = 0; t < 3; ++t) area += 0.5f * length(geometric_normal(m, t));
  EXPECT_NEAR(area, 2.5f * std::sin(72.0f * 3.14159265f / 180.0f), 1e-5f);
}

TEST(PlyLoader, BinaryLittleEndianRoundTrip) {
  const std::string path = tmp_path("fixture_le.ply");
  write_file(path, fixture_binary(false, false));
  expect_fixture(load_ply(path));
}

TEST(PlyLoader, BinaryBigEndianRoundTrip) {
  const std::string path = tmp_path("fixture_be.ply");
  write_file(path, fixture_binary(true, false));
  expect_fixture(load_ply(path));
}

TEST(PlyLoader, GenericFacePathMatchesFastPath) {
  // An extra face property forces the generic record walker in both byte orders.
  expect_fixture(parse_ply(fixture_binary(false, true), "le_generic.ply"));
  expect_fixture(parse_ply(fixture_binary(true, true), "be_generic.ply"));
}

// Every scalar type and spelling, for coordinates and for list count/index types, in both byte orders, with extra
// elements and properties that must be skipped.
TEST(PlyLoader, EveryScalarTypeBothByteOrders) {
  struct Type {
    const char* name;
    int size;
    bool is_signed;
    bool is_float;
  };
  const Type kTypes[] = {
      {"char", 1, true, false},  {"int8", 1, true, false},   {"uchar", 1, false, false},  {"uint8", 1, false, false},
      {"short", 2, true, false}, {"int16", 2, true, false},  {"ushort", 2, false, false}, {"uint16", 2, false, false},
      {"int", 4, true, false},   {"int32", 4, true, false},  {"uint", 4, false, false},   {"uint32", 4, false, false},
      {"float", 4, true, true},  {"float32", 4, true, true}, {"double", 8, true, true},   {"float64", 8, true, true}};
  auto put = [](Bytes& b, const Type& t, double v) {
    if (t.is_float) {
      if (t.size == 4)
        b.put(float(v));
      else
        b.put(v);
    } else if (t.size == 1) {
      if (t.is_signed)
        b.put(int8_t(v));
      else
        b.put(uint8_t(v));
    } else if (t.size == 2) {
      if (t.is_signed)
        b.put(int16_t(v));
      else
        b.put(uint16_t(v));
    } else {
      if (t.is_signed)
        b.put(int32_t(v));
      else
        b.put(uint32_t(v));
    }
  };
  const double coords[4][3] = {{0, 0, 0}, {3, 0, 0}, {3, 5, 0}, {0, 5, 7}};
  for (bool big : {false, true}) {
    for (const Type& t : kTypes) {
      for (const Type& count_type : kTypes) {
        if (count_type.is_float) continue;
        const Type& index_type = count_type;  // indices in the same integer type as the count
        std::string h = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                        " 1.0\nelement vertex 4\nproperty " + t.name + " x\nproperty uchar confidence\nproperty " +
                        t.name + " y\nproperty " + t.name +
                        " z\nproperty float texture_u\nproperty float texture_v\n"
                        "element edge 1\nproperty int vertex1\nproperty list uchar int extra\n"
                        "element face 1\nproperty list " +
                        count_type.name + " " + index_type.name +
                        " vertex_index\nproperty double quality\nend_header\n";
        Bytes b(big);
        for (int i = 0; i < 4; ++i) {
          put(b, t, coords[i][0]);
          b.put(uint8_t(200));
          put(b, t, coords[i][1]);
          put(b, t, coords[i][2]);
          b.put(float(i) * 0.25f).put(1.0f - float(i) * 0.25f);
        }
        b.put(int32_t(1)).put(uint8_t(2)).put(int32_t(-9)).put(int32_t(-9));  // edge record, skipped
        put(b, count_type, 4);
        for (int v : {0, 1, 2, 3}) put(b, index_type, v);
        b.put(0.5);
        const std::string what = std::string(big ? "BE " : "LE ") + t.name + " / " + count_type.name;
        MeshDesc m;
        ASSERT_NO_THROW(m = parse_ply(h + b.str(), "types.ply")) << what;
        ASSERT_EQ(m.positions.size(), 4u) << what;
        for (int i = 0; i < 4; ++i)
          EXPECT_EQ(m.positions[size_t(i)], Vec3f(float(coords[i][0]), float(coords[i][1]), float(coords[i][2])))
              << what << " vertex " << i;
        ASSERT_EQ(m.uvs.size(), 4u) << what;
        EXPECT_EQ(m.uvs[3].x, 0.75f) << what;
        EXPECT_EQ(m.uvs[3].y, 0.25f) << what;
        EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3})) << what;
      }
    }
  }
}

TEST(PlyLoader, TruncationAtEveryByteIsAnErrorNeverACrash) {
  for (bool generic : {false, true}) {
    const std::string full = fixture_binary(false, generic);
    const size_t header_end = full.find("end_header\n") + 11;
    for (size_t cut = 0; cut < full.size(); ++cut) {
      const std::string msg = error_of([&] { parse_ply(full.substr(0, cut), "cut.ply"); });
      EXPECT_NE(msg.find("cut.ply"), std::string::npos) << cut << ": " << msg;
      if (cut >= header_end) {
        EXPECT_NE(msg.find("truncated"), std::string::npos) << cut << ": " << msg;
      }
    }
  }
}

TEST(PlyLoader, AsciiTruncationIsAnError) {
  const std::string full =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_NO_THROW(parse_ply(full, "ok.ply"));
  const size_t body = full.find("end_header\n") + 11;
  for (size_t cut = body; cut + 1 < full.size(); ++cut) {  // the final '\n' is optional
    const std::string msg = error_of([&] { parse_ply(full.substr(0, cut), "cut.ply"); });
    EXPECT_NE(msg.find("truncated"), std::string::npos) << cut << ": " << msg;
  }
}

TEST(PlyLoader, IndexOutOfRangeIsAnErrorOnEveryPath) {
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n";
  std::string msg = error_of([&] { parse_ply(ascii, "bad.ply"); });
  EXPECT_NE(msg.find("bad.ply"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 14"), std::string::npos) << msg;
  EXPECT_NE(msg.find("vertex index 3 is out of range (3 vertices)"), std::string::npos) << msg;

  for (bool generic : {false, true}) {
    for (int32_t bad : {5, -1}) {
      std::string h =
          "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
          "property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
      if (generic) h += "property uchar flags\n";
      h += "end_header\n";
      Bytes b(false);
      for (int i = 0; i < 9; ++i) b.put(float(i));
      b.put(uint8_t(3)).put(int32_t(0)).put(bad).put(int32_t(1));
      if (generic) b.put(uint8_t(0));
      msg = error_of([&] { parse_ply(h + b.str(), "bad.ply"); });
      EXPECT_NE(msg.find("element 'face' #0"), std::string::npos) << msg;
      EXPECT_NE(msg.find("vertex index " + std::to_string(bad) + " is out of range"), std::string::npos) << msg;
    }
  }
}

TEST(PlyLoader, FacesWithFewerThanThreeVerticesAreErrors) {
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n";
  EXPECT_NE(error_of([&] { parse_ply(ascii, "short.ply"); }).find("face has 2 vertices"), std::string::npos);
}

TEST(PlyLoader, BadHeadersAreErrors) {
  const std::string vertex = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string face = "element face 0\nproperty list uchar int vertex_indices\n";
  const struct {
    std::string text, expect;
  } cases[] = {
      {"PLY\n", "not a PLY file"},
      {"ply\nformat ascii 1.0\n" + vertex + face, "missing end_header"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "property before any element"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n", "unknown type 'float128'"},
      {"ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", "is not a count"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n",
       "list count type must be an integer"},
      {"ply\nformat binary_middle_endian 1.0\n" + vertex + face + "end_header\n", "unknown format"},
      {"ply\n" + vertex + face + "end_header\n", "missing format line"},
      {"ply\nformat ascii 1.0\n" + face + "end_header\n", "no 'vertex' element"},
      {"ply\nformat ascii 1.0\n" + vertex + "end_header\n0 0 0\n", "no 'face' element"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n" + face + "end_header\n0 0\n",
       "missing property 'z'"},
      {"ply\nformat ascii 1.0\n" + vertex + "element face 0\nproperty list uchar float vertex_indices\nend_header\n",
       "vertex index type must be an integer"},
      {"ply\nformat ascii 1.0\n" + vertex + "element face 0\nproperty list uchar int corners\nend_header\n",
       "no vertex_indices"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
       "property float nx\n" +
           face + "end_header\n0 0 0 1\n",
       "normals need all of nx, ny, nz"},
  };
  for (const auto& c : cases) {
    const std::string msg = error_of([&] { parse_ply(c.text, "hdr.ply"); });
    EXPECT_NE(msg.find(c.expect), std::string::npos) << "expected '" << c.expect << "' in: " << msg;
    EXPECT_EQ(msg.rfind("hdr.ply", 0), 0u) << msg;
  }
}

TEST(PlyLoader, NonFiniteAndNonNumericValuesAreErrors) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (const char* bad : {"nan", "inf", "1e999", "abc", "1.5.2"}) {
    const std::string msg = error_of([&] { parse_ply(head + "0 0 0\n1 " + bad + " 0\n0 1 0\n3 0 1 2\n", "nan.ply"); });
    EXPECT_NE(msg.find("line 11"), std::string::npos) << bad << ": " << msg;
  }
  // Binary NaN coordinate.
  std::string h =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  Bytes b(false);
  for (int i = 0; i < 9; ++i) b.put(i == 4 ? std::nanf("") : float(i));
  b.put(uint8_t(3)).put(int32_t(0)).put(int32_t(1)).put(int32_t(2));
  const std::string msg = error_of([&] { parse_ply(h + b.str(), "nan.ply"); });
  EXPECT_NE(msg.find("element 'vertex' #1: non-finite position"), std::string::npos) << msg;
  // Integer list index written as a float in ASCII.
  EXPECT_NE(
      error_of([&] { parse_ply(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", "f.ply"); }).find("expected an integer"),
      std::string::npos);
}

TEST(PlyLoader, HugeDeclaredCountsFailBeforeAllocating) {
  const std::string h =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_NE(error_of([&] { parse_ply(h + std::string(64, '\0'), "huge.ply"); }).find("truncated"), std::string::npos);
  const std::string h2 =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 9223372036854775807\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_NE(error_of([&] { parse_ply(h2 + std::string(36, '\0'), "huge.ply"); }).find("truncated"), std::string::npos);
}

TEST(PlyLoader, MissingFileNamesIt) {
  const std::string msg = error_of([] { load_ply("/nonexistent/dir/mesh.ply"); });
  EXPECT_NE(msg.find("/nonexistent/dir/mesh.ply"), std::string::npos) << msg;
}

// A 1M-triangle binary grid through the fast path: checks the counts and reports the decode rate.
TEST(PlyLoader, LargeBinaryMeshDecodesFast) {
  constexpr int kN = 708;  // (kN+1)^2 vertices, 2 kN^2 ~ 1.0M triangles
  const size_t nv = size_t(kN + 1) * (kN + 1), nf = size_t(2) * kN * kN;
  std::string data = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(nv) +
                     "\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\n"
                     "element face " +
                     std::to_string(nf) + "\nproperty list uchar int vertex_indices\nend_header\n";
  Bytes b(false);
  for (int j = 0; j <= kN; ++j)
    for (int i = 0; i <= kN; ++i) b.put(float(i)).put(float(j)).put(0.0f).put(float(i) / kN).put(float(j) / kN);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const int32_t v = j * (kN + 1) + i;
      b.put(uint8_t(3)).put(v).put(v + 1).put(v + kN + 2);
      b.put(uint8_t(3)).put(v).put(v + kN + 2).put(v + kN + 1);
    }
  data += b.str();
  const auto t0 = std::chrono::steady_clock::now();
  const MeshDesc m = parse_ply(data, "grid.ply");
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(m.positions.size(), nv);
  ASSERT_EQ(m.indices.size(), 3 * nf);
  EXPECT_EQ(m.positions.back(), Vec3f(float(kN), float(kN), 0));
  EXPECT_EQ(m.indices[3 * nf - 1], uint32_t(nv - 2));
  std::printf("[ info ] decoded %zu triangles (%.1f MB) in %.1f ms\n", nf, double(data.size()) / 1e6, ms);
  RecordProperty("decode_ms", std::to_string(ms));
}

}  // namespace
}  // namespace kiln
