#include "scenes/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/error.h"
#include "scenes/parse_util.h"

namespace kiln {
namespace {

// ---- Pre-scan: tinyobjloader accepts out-of-range indices (it only warns, naming the last line) and reads
// malformed numbers as 0, so every line it would use is checked here first, with the offending line number.

// Space and tab only, as tinyobjloader separates tokens (split_whitespace would also split at \f and \v).
bool is_blank(char c) { return c == ' ' || c == '\t'; }

// Fills `tokens` (cleared first) so that one buffer serves every line: a vector per line was half the time of a
// fuzzing run under AddressSanitizer.
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

struct ElementCounts {
  long long v = 0, vt = 0, vn = 0;
};

// The statements Kiln uses; every other line is ignored (see ScannedObj).
enum class Statement { Other, Position, TexCoord, Normal, Face };

// The statement a line starts with: its first token, after spaces and tabs, is v, vt, vn or f. Looks at no more
// than three characters of the token: every line of the file goes through here, and scanning a whole token (a
// mutated line is often one long token) character by character was a fifth of the fuzzing harness's time.
Statement statement_of(std::string_view line) {
  size_t i = 0;
  while (i < line.size() && is_blank(line[i])) ++i;
  const auto token_ends_at = [&](size_t j) { return j >= line.size() || is_blank(line[j]); };
  if (i == line.size()) return Statement::Other;
  if (line[i] == 'f') return token_ends_at(i + 1) ? Statement::Face : Statement::Other;
  if (line[i] != 'v') return Statement::Other;
  if (token_ends_at(i + 1)) return Statement::Position;
  if (!token_ends_at(i + 2)) return Statement::Other;
  return line[i + 1] == 't' ? Statement::TexCoord : line[i + 1] == 'n' ? Statement::Normal : Statement::Other;
}

struct UsedLine {
  std::string_view text;
  int number;
  Statement statement;
};

// Position of the next `c` at or after `from` in `text`, or text.size().
size_t next_of(std::string_view text, char c, size_t from) {
  const void* hit = std::memchr(text.data() + from, c, text.size() - from);
  return hit ? size_t(static_cast<const char*>(hit) - text.data()) : text.size();
}

// Calls f(line, line_number) for each line; lines end in \n, \r\n or a lone \r, as tinyobjloader reads them.
// Line ends are found with memchr, the next \n and the next \r each searched again only once passed: a
// character-by-character search (std::string::find_first_of calls memchr on the set for every character) was a
// quarter of the OBJ fuzzing harness's time.
template <typename F>
void for_each_line(std::string_view text, F&& f) {
  const size_t n = text.size();
  size_t next_lf = next_of(text, '\n', 0), next_cr = next_of(text, '\r', 0);
  int line_no = 1;
  for (size_t start = 0; start < n; ++line_no) {
    if (next_lf < start) next_lf = next_of(text, '\n', start);
    if (next_cr < start) next_cr = next_of(text, '\r', start);
    size_t end = std::min(next_lf, next_cr);
    f(std::string_view(text.data() + start, end - start), line_no);
    if (end == next_cr && end + 1 == next_lf) ++end;  // \r\n
    start = end + 1;
  }
}

// One pass over the text: the lines Kiln uses, the element totals (face indices may refer forward), and the text
// tinyobjloader parses: only the statements Kiln uses and the validator checks (v, vt, vn, f).
// Every other line (groups, materials, lines, points, tags, skin weights, ...) is blanked, keeping line numbers:
// Kiln ignores those statements, and tinyobjloader parses them unchecked (a `vw` joint id of 1e99 is converted
// to int, undefined behaviour; each `t` tag line allocates up to 3 x 8192 values, so a 64 KB file of them
// allocates gigabytes). Emptied rather than overwritten with spaces: tinyobjloader copies a line character by
// character before looking at it.
struct ScannedObj {
  std::vector<UsedLine> lines;
  ElementCounts totals;
  std::string used_statements;
};

ScannedObj scan_obj(std::string_view text) {
  ScannedObj scan;
  scan.used_statements.reserve(text.size());
  for_each_line(text, [&](std::string_view line, int line_no) {
    const Statement statement = statement_of(line);
    if (statement != Statement::Other) {
      scan.lines.push_back({line, line_no, statement});
      scan.used_statements += line;
    }
    scan.used_statements += '\n';
    scan.totals.v += statement == Statement::Position;
    scan.totals.vt += statement == Statement::TexCoord;
    scan.totals.vn += statement == Statement::Normal;
  });
  return scan;
}

class ObjValidator {
 public:
  ObjValidator(const std::string& source, ElementCounts totals) : source_(source), totals_(totals) {}

  void line(const UsedLine& used) {
    line_no_ = used.number;
    split_tokens(used.text, tokens_);
    switch (used.statement) {
      case Statement::Position:
        numbers(tokens_, 3, 6, "vertex position 'v'");
        ++counts_.v;
        break;
      case Statement::TexCoord:
        numbers(tokens_, 1, 3, "texture coordinate 'vt'");
        ++counts_.vt;
        break;
      case Statement::Normal:
        numbers(tokens_, 3, 3, "vertex normal 'vn'");
        ++counts_.vn;
        break;
      case Statement::Face:
        face(tokens_);
        break;
      case Statement::Other:
        break;
    }
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(source_, "line " + std::to_string(line_no_), message);
  }

  void numbers(const std::vector<std::string_view>& tokens, size_t min_count, size_t max_count,
               const char* what) const {
    const size_t n = tokens.size() - 1;
    if (n < min_count || n > max_count) {
      fail(std::string(what) + " needs " +
           (min_count == max_count ? std::to_string(min_count)
                                   : std::to_string(min_count) + " to " + std::to_string(max_count)) +
           " numbers, got " + std::to_string(n));
    }
    for (size_t i = 1; i < tokens.size(); ++i) {
      if (!to_float(tokens[i]))
        fail(std::string(what) + ": '" + std::string(tokens[i]) + "' is not a finite number");
    }
  }

  // One index of a face vertex: 1-based into the whole file (tinyobjloader resolves them after reading it all,
  // so forward references work), or negative, relative to the elements defined before this line.
  void index(std::string_view s, long long defined_so_far, long long total, const char* element,
             const char* elements) const {
    const std::optional<int64_t> parsed = to_int64(s);
    if (!parsed) fail("face index '" + std::string(s) + "' is not an integer");
    const long long value = *parsed;
    if (value == 0) fail("face index 0 is invalid (OBJ indices start at 1; negative ones are relative)");
    const auto plural = [&](long long n) {
      return std::to_string(n) + " " + (n == 1 ? element : elements);
    };
    if (value > 0 && value > total)
      fail("face " + std::string(element) + " index " + std::string(s) + " is out of range (the file defines " +
           plural(total) + ")");
    if (value < 0 && defined_so_far + value < 0)
      fail("relative face " + std::string(element) + " index " + std::string(s) + " is out of range (" +
           plural(defined_so_far) + " defined before this line)");
  }

  void face(const std::vector<std::string_view>& tokens) const {
    if (tokens.size() < 4)
      fail("face 'f' needs at least 3 vertices, got " + std::to_string(tokens.size() - 1));
    for (size_t i = 1; i < tokens.size(); ++i) {
      // v, v/vt, v//vn or v/vt/vn
      std::string_view t = tokens[i];
      std::string_view parts[3];
      int n = 0;
      size_t start = 0;
      for (;;) {
        const size_t slash = t.find('/', start);
        if (n == 3) fail("face vertex '" + std::string(t) + "' has more than three '/'-separated indices");
        parts[n++] = t.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
        if (slash == std::string_view::npos) break;
        start = slash + 1;
      }
      index(parts[0], counts_.v, totals_.v, "vertex", "vertices");
      if (n == 2 || (n == 3 && !parts[1].empty()))
        index(parts[1], counts_.vt, totals_.vt, "texture coordinate", "texture coordinates");
      if (n == 3) index(parts[2], counts_.vn, totals_.vn, "normal", "normals");
    }
  }

  const std::string& source_;
  ElementCounts totals_;  // in the whole file
  ElementCounts counts_;  // before the current line
  int line_no_ = 0;
  std::vector<std::string_view> tokens_;  // of the current line
};

void validate_obj_lines(const ScannedObj& scan, const std::string& source) {
  ObjValidator validator(source, scan.totals);
  for (const UsedLine& line : scan.lines) validator.line(line);
}

// ---- Conversion of tinyobjloader's output to a MeshDesc.

struct VertexKey {
  int v, vt, vn;
  bool operator==(const VertexKey&) const = default;
};

struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    uint64_t h = static_cast<uint32_t>(k.v);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(k.vt);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(k.vn);
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

Vec3f attrib_vec3(const std::vector<tinyobj::real_t>& data, int i) {
  const size_t b = 3 * static_cast<size_t>(i);
  return {static_cast<float>(data[b]), static_cast<float>(data[b + 1]), static_cast<float>(data[b + 2])};
}

// Flips triangle t when its geometric normal disagrees with its vertex normals (see the header).
void orient_by_normals(MeshDesc& mesh, size_t t) {
  uint32_t* tri = &mesh.indices[3 * t];
  const Vec3f p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
  const Vec3f ng = cross(p1 - p0, p2 - p0);
  const Vec3f ns = mesh.normals[tri[0]] + mesh.normals[tri[1]] + mesh.normals[tri[2]];
  if (dot(ng, ns) < 0.0f) std::swap(tri[1], tri[2]);
}

MeshDesc build_mesh(const tinyobj::attrib_t& attrib, const std::vector<tinyobj::shape_t>& shapes,
                    const std::string& source) {
  size_t corner_count = 0;
  bool all_normals = !attrib.normals.empty();
  bool all_uvs = !attrib.texcoords.empty();
  for (const auto& shape : shapes) {
    corner_count += shape.mesh.indices.size();
    for (const auto& idx : shape.mesh.indices) {
      all_normals = all_normals && idx.normal_index >= 0;
      all_uvs = all_uvs && idx.texcoord_index >= 0;
    }
  }
  if (corner_count == 0) throw Error(source, "", "the OBJ file has no faces");

  MeshDesc mesh;
  mesh.name = source;
  mesh.indices.reserve(corner_count);
  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> remap;
  remap.reserve(corner_count);
  const int num_positions = static_cast<int>(attrib.vertices.size() / 3);
  for (const auto& shape : shapes) {
    for (int fv : shape.mesh.num_face_vertices) {
      if (fv != 3) throw Error(source, "", "tinyobjloader left a face with " + std::to_string(fv) + " vertices");
    }
    for (const auto& idx : shape.mesh.indices) {
      // Validated by the pre-scan; re-checked so a tinyobjloader change cannot read out of bounds.
      if (idx.vertex_index < 0 || idx.vertex_index >= num_positions)
        throw Error(source, "", "face vertex index out of range after parsing");
      const VertexKey key{idx.vertex_index, all_uvs ? idx.texcoord_index : -1, all_normals ? idx.normal_index : -1};
      auto [it, inserted] = remap.try_emplace(key, static_cast<uint32_t>(mesh.positions.size()));
      if (inserted) {
        mesh.positions.push_back(attrib_vec3(attrib.vertices, key.v));
        if (all_normals) mesh.normals.push_back(attrib_vec3(attrib.normals, key.vn));
        if (all_uvs) {
          const size_t b = 2 * static_cast<size_t>(key.vt);
          mesh.uvs.emplace_back(static_cast<float>(attrib.texcoords[b]), static_cast<float>(attrib.texcoords[b + 1]));
        }
      }
      mesh.indices.push_back(it->second);
    }
  }
  if (all_normals) {
    for (size_t t = 0; t < mesh.indices.size() / 3; ++t) orient_by_normals(mesh, t);
  }
  return mesh;
}

// tinyobjloader parses numbers with its own routine, which can turn text the pre-scan accepts as finite (e.g.
// "0.E473882", zero with an out-of-range exponent: 0 * inf) into NaN or inf; what it read is checked again.
void require_finite(const std::vector<tinyobj::real_t>& values, size_t per_element, const char* what,
                    const std::string& source_name) {
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw Error(source_name, "", std::string(what) + " number " + std::to_string(i / per_element + 1) +
                                       " does not read as a finite number (an exponent out of range?)");
}

}  // namespace

MeshDesc parse_obj(std::string_view text, const std::string& source_name) {
  ScannedObj scan = scan_obj(text);
  validate_obj_lines(scan, source_name);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  std::istringstream stream(std::move(scan.used_statements));
  // No MaterialReader: `mtllib` is ignored (materials come from the scene file).
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &stream, nullptr,
                                   /*triangulate=*/true, /*default_vcols_fallback=*/false);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == '.')) err.pop_back();
    throw Error(source_name, "", "tinyobjloader: " + (err.empty() ? std::string("parse failed") : err));
  }
  require_finite(attrib.vertices, 3, "vertex position 'v'", source_name);
  require_finite(attrib.normals, 3, "vertex normal 'vn'", source_name);
  require_finite(attrib.texcoords, 2, "texture coordinate 'vt'", source_name);
  return build_mesh(attrib, shapes, source_name);
}

MeshDesc load_obj(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path, "", "OBJ file does not exist");
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path, "", "not a regular file");
  return parse_obj(read_file_bytes(path), path);
}

}  // namespace kiln
