// What each loader harness does with one input, shared by the libFuzzer harnesses (tests/fuzz/fuzz_*.cpp) and by
// the regression test that replays the corpora and the saved crashes in the normal suite
// (tests/scenes/fuzz_regression_test.cpp), so both exercise exactly the same code.
//
// The contract under test: a loader either throws kiln::Error, or returns a description the renderer can use
// as-is: every index in range, every number finite (check_mesh / check_scene; a violation throws
// InvariantViolation). Any exception other than kiln::Error escapes, and aborts the fuzzer as an uncaught
// exception; crashes, leaks and sanitizer reports are the sanitizers' business.
//
// PLY, OBJ and pbrt have in-memory entry points (pbrt's as though the text were `scratch/input.pbrt`, so its
// Include, Import and plymesh names resolve in the scratch folder). The XML and JSON loaders only take a path, so the
// input is written to `scratch/input.xml` (`.json`) first. The scratch folder also holds small fixture files with
// fixed names that the seeds reference (plyFile="fixture.ply", binaryFile="vertices.bin", obj_file_path
// "fixture.obj", Include "fixture_include.pbrt", plymesh "fixture.ply.gz", ...), so mutated scenes reach the code
// behind a successful reference and not only the "cannot open" error.
#pragma once
#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scenes/gzip_file.h"
#include "scenes/json_loader.h"
#include "scenes/obj_loader.h"
#include "scenes/pbrt/loader.h"
#include "scenes/ply_loader.h"
#include "scenes/xml_loader.h"

namespace kiln::fuzz {

enum class Loader { Ply, Obj, Xml, Json, Pbrt };
inline constexpr std::array<Loader, 5> kLoaders = {Loader::Ply, Loader::Obj, Loader::Xml, Loader::Json, Loader::Pbrt};

// Folder name under tests/fuzz/corpus/ and tests/fuzz/regressions/, and the input file extension.
inline std::string_view loader_name(Loader l) {
  switch (l) {
    case Loader::Ply:
      return "ply";
    case Loader::Obj:
      return "obj";
    case Loader::Xml:
      return "xml";
    case Loader::Json:
      return "json";
    case Loader::Pbrt:
      return "pbrt";
  }
  return "unknown";
}

inline std::optional<Loader> loader_from_name(std::string_view name) {
  for (Loader l : kLoaders)
    if (loader_name(l) == name) return l;
  return std::nullopt;
}

// open/write/close rather than an ofstream: the stream's 8 KB buffer, allocated for every input, cost the XML and
// JSON harnesses a tenth of their time under AddressSanitizer.
inline void write_bytes(const std::filesystem::path& path, std::string_view bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  bool ok = fd >= 0;
  for (size_t done = 0; ok && done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    ok = n > 0;
    if (ok) done += size_t(n);
  }
  if (fd >= 0) ok = ::close(fd) == 0 && ok;
  if (!ok) throw std::runtime_error("cannot write fuzz scratch file " + path.string());
}

// The course's binaryFile layout: little-endian int32 count, then the 4-byte values.
template <typename T>
std::string little_endian_block(int32_t count, std::initializer_list<T> values) {
  static_assert(sizeof(T) == 4);
  std::string out;
  auto put = [&](uint32_t u) {
    for (int b = 0; b < 4; ++b) out.push_back(char((u >> (8 * b)) & 0xFFu));
  };
  put(uint32_t(count));
  for (T v : values) {
    uint32_t u;
    std::memcpy(&u, &v, 4);
    put(u);
  }
  return out;
}

// Fixture files the seeds refer to by name; all valid, all tiny.
inline void write_fixtures(const std::filesystem::path& dir) {
  write_bytes(dir / "fixture.ply",
              "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
              "property float u\nproperty float v\nelement face 1\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n");
  std::string binary_ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  binary_ply += little_endian_block<float>(0, {0, 0, 0, 1, 0, 0, 0, 1, 0}).substr(4);
  binary_ply += '\3';
  binary_ply += little_endian_block<int32_t>(0, {0, 1, 2}).substr(4);
  write_bytes(dir / "fixture_binary.ply", binary_ply);
  write_bytes(dir / "fixture.obj",
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
              "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
  write_bytes(dir / "vertices.bin", little_endian_block<float>(3, {0, 0, 0, 1, 0, 0, 0, 1, 0}));
  write_bytes(dir / "texcoords.bin", little_endian_block<float>(3, {0, 0, 1, 0, 0, 1}));
  write_bytes(dir / "faces.bin", little_endian_block<int32_t>(1, {1, 2, 3}));
  // Environment maps must exist when a scene names one (the loader checks; the renderer reads it).
  write_bytes(dir / "env.hdr", "#?RADIANCE\n");
  const std::string ply_text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
  write_bytes(dir / "fixture.ply.gz", gzip(ply_text));
  write_bytes(dir / "fixture_include.pbrt",
              "AttributeBegin\n  Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"float roughness\" 0.1\n"
              "  Translate 0 0 1\n  Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n"
              "AttributeEnd\n");
  write_bytes(dir / "fixture.spd", "# wavelength value\n400 0.2\n500 0.5\n600 0.8\n700 0.9\n");
}

// A loader returned a description that breaks the SceneDesc contract (a finding, like a crash).
class InvariantViolation : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

inline void require(bool ok, const std::string& what) {
  if (!ok) throw InvariantViolation("loader accepted the input but " + what);
}

inline bool finite(float x) { return std::isfinite(x); }
inline bool finite(Vec3f v) { return is_finite(v); }
inline bool finite(Vec2f v) { return std::isfinite(v.x) && std::isfinite(v.y); }
inline bool finite(const Rgb& c) { return c.is_finite(); }
inline bool finite(const Mat4& m) {
  for (const auto& row : m.m)
    for (float x : row)
      if (!std::isfinite(x)) return false;
  return true;
}
inline bool finite(const Transform& t) { return finite(t.matrix()) && finite(t.inverse_matrix()); }
template <typename T>
bool all_finite(const std::vector<T>& v) {
  for (const auto& x : v)
    if (!finite(x)) return false;
  return true;
}

// Loaders normalise area-light normals; float rounding leaves them within a few ulps of unit length.
inline constexpr float kUnitTolerance = 1e-4f;

inline void check_mesh(const MeshDesc& m) {
  const std::string name = "mesh '" + m.name + "' ";
  require(m.indices.size() % 3 == 0, name + "has an index count that is not a multiple of 3");
  for (uint32_t i : m.indices) require(i < m.positions.size(), name + "has an index out of range");
  require(m.normals.empty() || m.normals.size() == m.positions.size(), name + "has a normal count mismatch");
  require(m.uvs.empty() || m.uvs.size() == m.positions.size(), name + "has a uv count mismatch");
  require(all_finite(m.positions) && all_finite(m.normals) && all_finite(m.uvs), name + "has non-finite data");
  require(finite(m.to_world), name + "has a non-finite transform");
  require(!m.emission || finite(*m.emission), name + "has a non-finite emission");
}

inline void check_scene(const SceneDesc& s) {
  const auto material_ok = [&](int m) { return m >= -1 && m < int(s.materials.size()); };
  for (const auto& m : s.meshes) {
    check_mesh(m);
    require(material_ok(m.material), "mesh '" + m.name + "' has a material index out of range");
  }
  for (const auto& sp : s.spheres) {
    require(material_ok(sp.material), "sphere '" + sp.name + "' has a material index out of range");
    require(finite(sp.center) && finite(sp.radius) && sp.radius > 0 && finite(sp.to_world),
            "sphere '" + sp.name + "' has a non-finite or non-positive centre, radius or transform");
  }
  for (const auto& in : s.instances) {
    require(in.base_mesh >= 0 && in.base_mesh < int(s.meshes.size()), "instance '" + in.name + "' has a bad base");
    require(material_ok(in.material), "instance '" + in.name + "' has a material index out of range");
    require(finite(in.to_world), "instance '" + in.name + "' has a non-finite transform");
  }
  for (const auto& m : s.materials)
    require(!m.brdf || (*m.brdf >= 0 && *m.brdf < int(s.brdfs.size())), "a material has a BRDF index out of range");
  for (const auto& c : s.cameras) {
    require(c.width > 0 && c.height > 0 && c.num_samples > 0, "camera '" + c.id + "' has an empty image");
    require(finite(c.position) && finite(c.gaze) && finite(c.up) && finite(c.fov_y_deg) && finite(c.near_distance),
            "camera '" + c.id + "' has a non-finite position, direction or field of view");
    for (float x : c.near_plane) require(finite(x), "camera '" + c.id + "' has a non-finite near plane");
  }
  for (const auto& l : s.point_lights)
    require(finite(l.position) && finite(l.intensity), "a point light is non-finite");
  for (const auto& l : s.directional_lights)
    require(finite(l.direction) && finite(l.radiance), "a directional light is non-finite");
  for (const auto& l : s.spot_lights)
    require(finite(l.position) && finite(l.direction) && finite(l.intensity), "a spot light is non-finite");
  for (const auto& l : s.infinite_lights) require(finite(l.radiance), "an infinite light is non-finite");
  const auto texture_ok = [&](int t) { return t >= -1 && t < int(s.pbrt_textures.size()); };
  for (size_t i = 0; i < s.pbrt_textures.size(); ++i)  // a texture reads only textures defined before it: no cycles
    for (const TexturedRgb& o : s.pbrt_textures[i].operands)
      require(o.texture < int(i) && finite(o.value), "a pbrt texture reads a later texture or a non-finite value");
  for (const auto& m : s.materials)
    if (m.pbrt) {
      bool ok = m.pbrt->eta.value > 0 && texture_ok(m.pbrt->displacement) && texture_ok(m.pbrt->normal_map);
      for_each_texturable(*m.pbrt, [&](const auto& p) { ok = ok && finite(p.value) && texture_ok(p.texture); });
      require(ok, "a pbrt material has a non-finite or invalid parameter");
    }
  for (const auto& c : s.cameras)
    if (c.filter)
      require(finite(c.filter->radius) && c.filter->radius > 0 && finite(c.filter->sigma) && c.filter->sigma > 0,
              "camera '" + c.id + "' has an invalid pixel filter");
  for (const auto& l : s.area_lights) {
    require(finite(l.position) && finite(l.normal) && finite(l.size) && finite(l.radiance) &&
                (!l.edges || (finite((*l.edges)[0]) && finite((*l.edges)[1]))),
            "an area light is non-finite");
    require(std::abs(length(l.normal) - 1.0f) < kUnitTolerance, "an area light normal is not a unit vector");
  }
}

// Outcome of one input: loaded (and passed the checks), or rejected with this kiln::Error message.
struct Outcome {
  bool loaded = true;
  std::string error;
};

// Feeds `data` to the loader. kiln::Error (bad input, expected) is caught; InvariantViolation and anything else
// propagate. `scratch` must hold the fixtures (write_fixtures) for XML and JSON.
inline Outcome run_loader(Loader loader, std::string_view data, const std::filesystem::path& scratch) {
  try {
    switch (loader) {
      case Loader::Ply:
        check_mesh(parse_ply(data, "fuzz.ply"));
        break;
      case Loader::Obj:
        check_mesh(parse_obj(data, "fuzz.obj"));
        break;
      case Loader::Xml: {
        const auto path = scratch / "input.xml";
        write_bytes(path, data);
        check_scene(load_ceng795_xml(path.string()));
        break;
      }
      case Loader::Json: {
        const auto path = scratch / "input.json";
        write_bytes(path, data);
        check_scene(load_cs171_json(path.string()));
        break;
      }
      case Loader::Pbrt:
        check_scene(parse_pbrt(std::string(data), (scratch / "input.pbrt").string()));
        break;
    }
  } catch (const Error& e) {
    return {false, e.what()};
  }
  return {};
}

// libFuzzer glue: a scratch folder per process (fork/jobs modes run several), holding the fixtures, removed at a
// normal exit. A crashing process leaves its few-KB folder behind, next to the crash input it belongs to.
// KILN_FUZZ_SCRATCH names its parent; else /dev/shm when present: the XML and JSON harnesses write every input to
// a file, and on a disk file system (ext4) that open/truncate/write/close was a third of their time.
inline const std::filesystem::path& harness_scratch() {
  static const std::filesystem::path dir = [] {
    const char* chosen = std::getenv("KILN_FUZZ_SCRATCH");
    const char* tmp = std::getenv("TMPDIR");
    std::error_code ec;
    const std::string parent = chosen && *chosen                         ? chosen
                               : std::filesystem::is_directory("/dev/shm", ec) ? "/dev/shm"
                               : tmp && *tmp                              ? tmp
                                                                          : "/tmp";
    std::string pattern = parent + "/kiln_fuzz_XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a fuzz scratch folder in " + pattern);
    write_fixtures(pattern);
    return std::filesystem::path(pattern);
  }();
  static const int cleanup = std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(harness_scratch(), ec);
  });
  (void)cleanup;
  return dir;
}

inline int harness_input(Loader loader, const uint8_t* data, size_t size) {
  run_loader(loader, std::string_view(reinterpret_cast<const char*>(data), size), harness_scratch());
  return 0;  // libFuzzer: keep the input's coverage
}

}  // namespace kiln::fuzz
