#include "scenes/pbrt/shapes.h"

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "scenes/gzip_file.h"
#include "scenes/ply_loader.h"

namespace kiln {
namespace {

// pbrt's default number of Loop subdivision levels.
constexpr int kDefaultLoopLevels = 3;

std::string shape_name(const std::string& type, const PbrtParams& ps) {
  return "Shape \"" + type + "\" (" + std::filesystem::path(ps.file()).filename().string() + ":" +
         std::to_string(ps.line()) + ")";
}

// Indices checked against the vertex count; `per` vertices per primitive.
std::vector<uint32_t> checked_indices(const PbrtParams& ps, const std::vector<int64_t>& idx, size_t vertices,
                                      size_t per, const char* what) {
  if (idx.size() % per != 0)
    ps.fail(ps.line(), "\"indices\" has " + std::to_string(idx.size()) + " values, not a multiple of " +
                           std::to_string(per) + " (" + what + ")");
  std::vector<uint32_t> out(idx.size());
  for (size_t i = 0; i < idx.size(); ++i) {
    if (idx[i] < 0 || uint64_t(idx[i]) >= vertices)
      ps.fail(ps.line(), "\"indices\" value " + std::to_string(idx[i]) + " (entry " + std::to_string(i) +
                             ") is out of range: \"P\" has " + std::to_string(vertices) + " points");
    out[i] = uint32_t(idx[i]);
  }
  return out;
}

void check_vertex_data(const PbrtParams& ps, const MeshDesc& m) {
  if (!m.normals.empty() && m.normals.size() != m.positions.size())
    ps.fail(ps.line(), "\"N\" has " + std::to_string(m.normals.size()) + " normals but \"P\" has " +
                           std::to_string(m.positions.size()) + " points");
  if (!m.uvs.empty() && m.uvs.size() != m.positions.size())
    ps.fail(ps.line(), "\"uv\" has " + std::to_string(m.uvs.size()) + " entries but \"P\" has " +
                           std::to_string(m.positions.size()) + " points");
}

std::vector<Vec3f> required_points(const PbrtParams& ps) {
  std::vector<Vec3f> p = ps.get_point3s("P");
  if (p.empty()) ps.fail(ps.line(), "needs \"point3 P\"");
  return p;
}

// Indices, or 0..n-1 when the list is absent and the shape has exactly one primitive of n vertices.
std::vector<int64_t> indices_or_single(const PbrtParams& ps, size_t vertices, size_t per, const char* what) {
  std::vector<int64_t> idx = ps.get_ints("indices");
  if (idx.empty()) {
    if (vertices != per)
      ps.fail(ps.line(), "needs \"integer indices\" (only a single " + std::string(what) + " of exactly " +
                             std::to_string(per) + " points may leave them out)");
    for (size_t i = 0; i < per; ++i) idx.push_back(int64_t(i));
  }
  return idx;
}

MeshDesc triangle_mesh(const PbrtParams& ps, const std::string& name) {
  MeshDesc m;
  m.name = name;
  m.positions = required_points(ps);
  m.indices = checked_indices(ps, indices_or_single(ps, m.positions.size(), 3, "triangle"), m.positions.size(), 3,
                              "3 per triangle");
  m.normals = ps.get_normals("N");
  m.uvs = ps.get_point2s("uv");
  check_vertex_data(ps, m);
  return m;
}

// pbrt's (u, v) of the patches' corners as per-vertex uvs; empty when a vertex is a different corner of two patches.
std::vector<Vec2f> patch_corner_uvs(const std::vector<uint32_t>& quads, size_t vertices) {
  constexpr Vec2f kUnset(-1.0f, -1.0f);
  const Vec2f corner[4] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  std::vector<Vec2f> uv(vertices, kUnset);
  for (size_t i = 0; i < quads.size(); ++i) {
    Vec2f& at = uv[quads[i]];
    const Vec2f want = corner[i % 4];
    if (at.x != kUnset.x && (at.x != want.x || at.y != want.y)) return {};
    at = want;
  }
  return uv;
}

MeshDesc bilinear_mesh(const PbrtParams& ps, const std::string& name, PbrtDiagnostics& diag,
                       std::vector<Vec2f>& patch_uvs) {
  MeshDesc m;
  m.name = name;
  m.positions = required_points(ps);
  const std::vector<uint32_t> quads =
      checked_indices(ps, indices_or_single(ps, m.positions.size(), 4, "patch"), m.positions.size(), 4, "4 per patch");
  m.normals = ps.get_normals("N");
  m.uvs = ps.get_point2s("uv");
  check_vertex_data(ps, m);
  if (m.uvs.empty()) patch_uvs = patch_corner_uvs(quads, m.positions.size());
  size_t non_planar = 0;
  m.indices.reserve(quads.size() / 4 * 6);
  for (size_t q = 0; q + 3 < quads.size(); q += 4) {
    const uint32_t v00 = quads[q], v10 = quads[q + 1], v01 = quads[q + 2], v11 = quads[q + 3];
    const Vec3f p00 = m.positions[v00], p10 = m.positions[v10], p01 = m.positions[v01], p11 = m.positions[v11];
    const Vec3f n = cross(p10 - p00, p01 - p00);
    const float len = length(n), diag_len = std::max(length(p11 - p00), length(p10 - p01));
    if (len > 0.0f && std::abs(dot(p11 - p00, n / len)) > kBilinearPlanarityTolerance * diag_len) ++non_planar;
    m.indices.insert(m.indices.end(), {v00, v10, v11, v00, v11, v01});
  }
  if (non_planar > 0) {
    diag.warn(ps, std::to_string(non_planar) + " of " + std::to_string(quads.size() / 4) +
                      " bilinear patches are not planar; each is rendered as two flat triangles");
    diag.unsupported("non-planar bilinear patches (two flat triangles each)");
  }
  return m;
}

MeshDesc loop_mesh(const PbrtParams& ps, const std::string& name) {
  MeshDesc m;
  m.name = name;
  m.positions = required_points(ps);
  m.indices = checked_indices(ps, indices_or_single(ps, m.positions.size(), 3, "triangle"), m.positions.size(), 3,
                              "3 per triangle");
  const int levels = ps.get_int("levels", kDefaultLoopLevels);
  if (levels < 0 || levels > kMaxSubdivisionLevels)
    ps.fail(ps.line(), "\"levels\" " + std::to_string(levels) + " is outside 0.." +
                           std::to_string(kMaxSubdivisionLevels) + " (each level multiplies the triangles by 4)");
  m.subdivide = levels;
  m.smooth = true;  // pbrt shades the limit surface with its normals
  return m;
}

// Empty when the file is missing and missing files are allowed (reported).
std::optional<MeshDesc> ply_mesh(const PbrtParams& ps, const std::string& name, const PbrtShapeContext& ctx) {
  const auto file = ps.find_string("filename");
  if (!file || file->empty()) ps.fail(ps.line(), "needs \"string filename\"");
  std::string path;
  try {
    path = ctx.resolve(*file, ps.line());
  } catch (const Error&) {
    if (!ctx.diagnostics.allow_missing_files) throw;
    for (const PbrtParam& p : ps.params()) p.used = true;
    ctx.diagnostics.missing_file(ps.file(), ps.line(), ps.context(), "PLY mesh " + in_quotes(*file) + " is missing");
    return std::nullopt;
  }
  MeshDesc m;
  try {
    m = parse_ply(read_file_maybe_gzip(path), path);
  } catch (const Error& e) {
    ps.fail(ps.line(), std::string("cannot load the PLY mesh: ") + e.what());
  }
  m.name = name + " " + std::filesystem::path(*file).filename().string();
  if (ps.has("displacement")) {
    ps.find_texture("displacement");
    ctx.diagnostics.warn(ps, "displacement is not rendered; the mesh is used undisplaced");
    ctx.diagnostics.unsupported("displacement (pbrt plymesh)");
  }
  if (ps.has("edgelength")) ps.get_float("edgelength", 1.0f);  // only meaningful with displacement
  return m;
}

QuadricDesc quadric(const PbrtParams& ps, const std::string& name, QuadricType type, float radius, float inner,
                    float height, float z_min, float z_max) {
  const QuadricOrError q = make_quadric(type, radius, inner, height, z_min, z_max, ps.get_float("phimax", 360.0f));
  if (!q.quadric) ps.fail(ps.line(), q.error);
  QuadricDesc d;
  d.name = name;
  d.quadric = *q.quadric;
  return d;
}

// A whole sphere is a SphereDesc (with its cone sampling as a light); one with cut-aways a quadric.
void sphere(const PbrtParams& ps, const std::string& name, PbrtShape& out) {
  const float r = ps.get_float("radius", 1.0f);
  if (!(r > 0.0f)) ps.fail(ps.line(), "\"radius\" must be positive");
  const float z_min = ps.get_float("zmin", -r), z_max = ps.get_float("zmax", r);
  if (std::min(z_min, z_max) > -r || std::max(z_min, z_max) < r || ps.get_float("phimax", 360.0f) < 360.0f) {
    out.quadric = quadric(ps, name, QuadricType::Sphere, r, 0.0f, 0.0f, z_min, z_max);
    return;
  }
  out.sphere = SphereDesc{};
  out.sphere->name = name;
  out.sphere->radius = r;
}

}  // namespace

PbrtShape make_pbrt_shape(const std::string& type, const PbrtParams& ps, const PbrtShapeContext& ctx) {
  const std::string name = shape_name(type, ps);
  PbrtShape out;
  if (type == "trianglemesh")
    out.mesh = triangle_mesh(ps, name);
  else if (type == "plymesh") {
    out.mesh = ply_mesh(ps, name, ctx);
    if (!out.mesh) return out;
  }
  else if (type == "loopsubdiv")
    out.mesh = loop_mesh(ps, name);
  else if (type == "bilinearmesh")
    out.mesh = bilinear_mesh(ps, name, ctx.diagnostics, out.patch_uvs);
  else if (type == "sphere")
    sphere(ps, name, out);
  else if (type == "disk")
    out.quadric = quadric(ps, name, QuadricType::Disk, ps.get_float("radius", 1.0f), ps.get_float("innerradius", 0.0f),
                          ps.get_float("height", 0.0f), 0.0f, 0.0f);
  else if (type == "cylinder")
    out.quadric = quadric(ps, name, QuadricType::Cylinder, ps.get_float("radius", 1.0f), 0.0f, 0.0f,
                          ps.get_float("zmin", -1.0f), ps.get_float("zmax", 1.0f));
  else if (type == "cone" || type == "paraboloid" || type == "hyperboloid") {
    ctx.diagnostics.warn(ps, "shape \"" + type + "\" is a pbrt-v3 shape that pbrt-v4 does not have; skipped");
    ctx.diagnostics.unsupported("pbrt-v3 shape \"" + type + "\"");
    for (const PbrtParam& p : ps.params()) p.used = true;
    return out;
  } else {
    ctx.diagnostics.warn(ps, "shape \"" + type + "\" is not supported; skipped");
    ctx.diagnostics.unsupported("pbrt shape \"" + type + "\"", LoadOutcome::Ignored);
    for (const PbrtParam& p : ps.params()) p.used = true;  // one warning for the shape, not one per parameter
    return out;
  }
  if (ps.has("alpha")) {
    const ShapeAlphaDesc alpha = ctx.alpha(ps);
    if (out.mesh) out.mesh->alpha = alpha;
    if (out.sphere) out.sphere->alpha = alpha;
    if (out.quadric) out.quadric->alpha = alpha;
  }
  return out;
}

}  // namespace kiln
