// Reading a pbrt-v4 file: tokens, directives, Include / Import, attribute and object blocks, transforms and the
// graphics state. The objects the directives describe are made by PbrtBuilder (scenes/pbrt/builder.h), shapes by
// scenes/pbrt/shapes.h and the camera by scenes/pbrt/camera.h.
#include "scenes/pbrt/loader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include "core/animated_transform.h"
#include "core/error.h"
#include "scenes/gzip_file.h"
#include "scenes/parse_util.h"
#include "scenes/pbrt/builder.h"
#include "scenes/pbrt/camera.h"
#include "scenes/pbrt/diagnostics.h"
#include "scenes/pbrt/params.h"
#include "scenes/pbrt/shapes.h"
#include "scenes/pbrt/tokenizer.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

using TransformPair = std::array<Transform, 2>;  // the transforms at shutter open and close (ActiveTransform)

// Attribute "shape" / "light" / "material" / "medium" / "texture" defaults in effect.
struct AttributeDefaults {
  std::shared_ptr<const PbrtParams> shape, light, material, medium, texture;
};

enum class BlockKind { Attribute, Object, Import };

struct GraphicsState {
  TransformPair ctm;
  std::array<bool, 2> active = {true, true};  // which of ctm ActiveTransform lets the transform directives change
  float transform_start = 0.0f, transform_end = 1.0f;  // TransformTimes (pbrt's time)
  bool reverse_orientation = false;
  int material = -1;  // index into SceneDesc::materials; -1: pbrt's default material
  std::optional<PbrtAreaLight> area_light;
  // MediumInterface in effect: references into PbrtParser::medium_refs_ (-1: no medium), resolved to media when
  // the file ends, since pbrt-v4 lets a scene name a medium (the camera's, typically) before defining it.
  MediumInterfaceDesc media;
  AttributeDefaults defaults;
};

struct Block {
  GraphicsState saved;
  BlockKind kind = BlockKind::Attribute;
  std::string file;
  int line = 0;
};

struct ObjectDef {
  std::vector<int> meshes;  // into SceneDesc::meshes (invisible prototypes)
  std::vector<SphereDesc> spheres;
  std::vector<QuadricDesc> quadrics;
};

struct OpenFile {
  std::unique_ptr<PbrtCursor> cursor;
  std::string dir;
  int included_at = 0;                  // line of the Include / Import in the parent file
  std::optional<size_t> import_blocks;  // Import: the block depth to return to when the file ends
};

bool same(const Transform& a, const Transform& b) { return a.matrix() == b.matrix(); }

// The matrix only: a singular transform (no inverse) is accepted until something needs its inverse.
bool finite_transform(const Transform& t) {
  for (const auto& row : t.matrix().m)
    for (float x : row)
      if (!std::isfinite(x)) return false;
  return true;
}

class PbrtParser {
 public:
  PbrtParser(const std::string& path, const PbrtOptions& options) : root_path_(path) {
    diag_.allow_missing_files = options.allow_missing_files;
    root_dir_ = fs::path(path).parent_path().string();
    if (root_dir_.empty()) root_dir_ = ".";
    scene_.source_path = path;
    scene_.format = "pbrt-v4";
    scene_.rules = SceneRules::Kiln;
    scene_.max_recursion_depth = kPbrtDefaultMaxDepth;
    // Directives the file leaves out still name the scene in messages about their defaults.
    camera_.camera = PbrtParams(path, "Camera", 0);
    camera_.film = PbrtParams(path, "Film", 0);
    camera_.sampler = PbrtParams(path, "Sampler", 0);
    camera_.filter = PbrtParams(path, "PixelFilter", 0);
  }

  SceneDesc run(std::string text) {
    push_file(std::move(text), root_path_, root_dir_, 0, std::nullopt);
    try {
      loop();
      finish();
    } catch (const Error& e) {
      // Errors inside included files also say where the inclusion happened.
      if (include_trace_.empty()) throw;
      throw Error(std::string(e.what()) + " (" + include_trace_ + ")");
    }
    return std::move(scene_);
  }

 private:
  // ---- files and tokens ----

  void push_file(std::string text, const std::string& path, const std::string& dir, int included_at,
                 std::optional<size_t> import_blocks) {
    if (files_.size() >= size_t(kPbrtMaxIncludeDepth))
      fail(
          included_at, "Include",
          "includes nest deeper than " + std::to_string(kPbrtMaxIncludeDepth) + " files (does a file include itself?)");
    OpenFile f;
    f.cursor = std::make_unique<PbrtCursor>(PbrtTokenizer(std::move(text), path));
    f.dir = dir;
    f.included_at = included_at;
    f.import_blocks = import_blocks;
    files_.push_back(std::move(f));
  }

  void loop() {
    while (!files_.empty()) {
      PbrtCursor& cur = *files_.back().cursor;
      const auto t = cur.next();
      if (!t) {
        close_file();
        continue;
      }
      update_trace();
      if (t->kind != PbrtTokenKind::Word) fail(t->line, "", "expected a directive, got " + pbrt_describe(*t));
      diag_.begin_directive(file(), t->line, std::string(t->text));
      directive(cur, *t);
      diag_.end_directive();
    }
  }

  void update_trace() {
    include_trace_.clear();
    for (size_t i = files_.size(); i-- > 1;)
      include_trace_ += (include_trace_.empty() ? "included from " : ", from ") + files_[i - 1].cursor->file() +
                        ": line " + std::to_string(files_[i].included_at);
  }

  void close_file() {
    OpenFile f = std::move(files_.back());
    files_.pop_back();
    if (files_.empty()) root_end_line_ = f.cursor->line();
    if (f.import_blocks) {
      // The imported file's attribute changes end with it.
      while (blocks_.size() > *f.import_blocks + 1) {
        diag_.warn(f.cursor->file(), blocks_.back().line, "AttributeBegin",
                   "is not closed by the end of the imported file");
        gs_ = blocks_.back().saved;
        blocks_.pop_back();
      }
      gs_ = blocks_.back().saved;
      blocks_.pop_back();
    }
  }

  const std::string& file() const { return files_.back().cursor->file(); }

  std::string location(int line, const std::string& context) const {
    std::string s = "line " + std::to_string(line);
    if (!context.empty()) s += " (" + context + ")";
    return s;
  }
  [[noreturn]] void fail(int line, const std::string& context, const std::string& message) const {
    throw Error(files_.empty() ? root_path_ : file(), location(line, context), message);
  }
  void warn(int line, const std::string& context, const std::string& message) {
    diag_.warn(file(), line, context, message);
  }

  PbrtToken next_token(PbrtCursor& cur, int line, const std::string& directive) {
    const auto t = cur.next();
    if (!t) fail(line, directive, "the file ends inside the directive");
    return *t;
  }

  float read_number(PbrtCursor& cur, int line, const std::string& directive) {
    const PbrtToken t = next_token(cur, line, directive);
    const auto v = t.kind == PbrtTokenKind::Word ? to_float(t.text) : std::nullopt;
    if (!v) fail(t.line, directive, "expected a finite number, got " + pbrt_describe(t));
    return *v;
  }

  template <size_t N>
  std::array<float, N> read_numbers(PbrtCursor& cur, int line, const std::string& directive, bool bracketed) {
    if (bracketed && next_token(cur, line, directive).kind != PbrtTokenKind::OpenBracket)
      fail(line, directive, "expected '[' and " + std::to_string(N) + " numbers");
    std::array<float, N> v{};
    for (float& x : v) x = read_number(cur, line, directive);
    if (bracketed) {
      const PbrtToken t = next_token(cur, line, directive);
      if (t.kind != PbrtTokenKind::CloseBracket)
        fail(t.line, directive, "expected ']' after " + std::to_string(N) + " numbers, got " + pbrt_describe(t));
    }
    return v;
  }

  std::string read_string(PbrtCursor& cur, int line, const std::string& directive) {
    const PbrtToken t = next_token(cur, line, directive);
    if (t.kind != PbrtTokenKind::String) fail(t.line, directive, "expected a quoted name, got " + pbrt_describe(t));
    return pbrt_unescape(t, file());
  }

  PbrtParams read_params(PbrtCursor& cur, int line, const std::string& context,
                         const std::shared_ptr<const PbrtParams>& defaults = nullptr) {
    PbrtParams ps(file(), context, line, files_.back().dir);
    diag_.name_directive(context);
    ps.set_defaults(defaults.get());
    ps.parse(cur);
    continue_params(ps, line, context);
    for (const PbrtParams::Remark& r : ps.remarks()) warn(r.line, context, r.message);
    return ps;
  }

  // pbrt reads one stream of tokens across the end of an included file, so a parameter list that an included file
  // ends may go on in the file that included it (the included file is closed by the main loop afterwards).
  void continue_params(PbrtParams& ps, int line, const std::string& context) {
    for (size_t i = files_.size(); i-- > 1;) {
      if (files_[i].cursor->peek()) return;  // the list ended inside this file
      PbrtCursor& outer = *files_[i - 1].cursor;
      const auto t = outer.peek();
      if (!t) continue;
      if (t->kind != PbrtTokenKind::String) return;
      warn(line, context,
           "the parameter list goes on after the end of this file, in " + outer.file() + " from line " +
               std::to_string(t->line) + " (read as one list, as pbrt does)");
      ps.parse(outer);
    }
  }

  // A file named in the scene: relative to the including file's folder, else to the main scene's folder.
  std::string resolve(const std::string& name, int line, const std::string& context) const {
    return resolve_in(files_.back().dir, file(), name, line, context);
  }
  // The same for a name written earlier in `file` (of folder `dir`), which may have been closed since.
  std::string resolve_in(const std::string& dir, const std::string& file, const std::string& name, int line,
                         const std::string& context) const {
    if (name.empty()) throw Error(file, location(line, context), "the file name is empty");
    const fs::path p(name);
    if (p.is_absolute()) return p.string();
    std::error_code ec;
    const fs::path local = fs::path(dir) / p;
    if (fs::is_regular_file(local, ec)) return local.lexically_normal().string();
    const fs::path from_root = fs::path(root_dir_) / p;
    if (fs::is_regular_file(from_root, ec)) return from_root.lexically_normal().string();
    throw Error(file, location(line, context),
                "cannot find " + in_quotes(name) + " (looked for " + local.lexically_normal().string() +
                    (local == from_root ? "" : " and " + from_root.lexically_normal().string()) + ")");
  }

  // ---- directives ----

  void directive(PbrtCursor& cur, const PbrtToken& t) {
    const std::string d(t.text);
    const int line = t.line;
    if (d == "AttributeBegin") return attribute_begin(line, BlockKind::Attribute);
    if (d == "AttributeEnd") return attribute_end(line, BlockKind::Attribute, "AttributeEnd");
    if (d == "TransformBegin" || d == "TransformEnd") {
      if (!warned_transform_block_)
        warn(line, d, "TransformBegin/End are deprecated in pbrt-v4 and read as AttributeBegin/End");
      warned_transform_block_ = true;
      if (d == "TransformBegin") return attribute_begin(line, BlockKind::Attribute);
      return attribute_end(line, BlockKind::Attribute, d);
    }
    if (d == "Translate") {
      const auto v = read_numbers<3>(cur, line, d, false);
      return apply(line, d, [&] { return Transform::translate({v[0], v[1], v[2]}); });
    }
    if (d == "Scale") {
      const auto v = read_numbers<3>(cur, line, d, false);
      return apply(line, d, [&] {
        Mat4 m = Mat4::identity();
        for (size_t i = 0; i < 3; ++i) m.m[i][i] = v[i];
        return Transform::from_matrix_maybe_singular(m);  // pbrt accepts a zero scale (a flattened shape)
      });
    }
    if (d == "Rotate") {
      const auto v = read_numbers<4>(cur, line, d, false);
      return apply(line, d, [&] { return Transform::rotate(v[0], {v[1], v[2], v[3]}); });
    }
    if (d == "LookAt") {
      const auto v = read_numbers<9>(cur, line, d, false);
      return apply(line, d, [&] { return look_at({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}, line); });
    }
    if (d == "Transform" || d == "ConcatTransform") {
      const auto v = read_numbers<16>(cur, line, d, true);
      Mat4 m;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m.m[r][c] = v[size_t(c * 4 + r)];  // the file lists the matrix by columns
      const Transform x = checked(line, d, [&] { return Transform::from_matrix_maybe_singular(m); });
      if (d == "Transform") return set_ctm(line, d, {x, x});
      return apply(line, d, [&] { return x; });
    }
    if (d == "Identity") return set_ctm(line, d, {Transform(), Transform()});
    if (d == "CoordinateSystem") {
      coord_systems_[read_string(cur, line, d)] = gs_.ctm;
      return;
    }
    if (d == "CoordSysTransform") {
      const std::string name = read_string(cur, line, d);
      const auto it = coord_systems_.find(name);
      if (it == coord_systems_.end()) {
        warn(line, d, "no coordinate system named " + in_quotes(name) + "; ignored");
        return diag_.unsupported("CoordSysTransform to an unknown coordinate system", LoadOutcome::Ignored);
      }
      gs_.ctm = it->second;
      return;
    }
    if (d == "ActiveTransform") {
      const PbrtToken a = next_token(cur, line, d);
      if (a.is_word("All"))
        gs_.active = {true, true};
      else if (a.is_word("StartTime"))
        gs_.active = {true, false};
      else if (a.is_word("EndTime"))
        gs_.active = {false, true};
      else
        fail(a.line, d, "expected All, StartTime or EndTime, got " + pbrt_describe(a));
      return;
    }
    if (d == "TransformTimes") {
      const auto v = read_numbers<2>(cur, line, d, false);
      require_options(line, d);
      if (!(v[1] > v[0])) fail(line, d, "the end time must be after the start time");
      gs_.transform_start = v[0];
      gs_.transform_end = v[1];
      return;
    }
    if (d == "ReverseOrientation") {
      gs_.reverse_orientation = !gs_.reverse_orientation;
      return;
    }
    if (d == "Include" || d == "Import") return include(cur, line, d);
    if (d == "Camera" || d == "Film" || d == "Sampler" || d == "PixelFilter") return option(cur, line, d);
    if (d == "Integrator") return integrator(cur, line);
    if (d == "Accelerator") {
      const std::string type = read_string(cur, line, d);
      PbrtParams ps = read_params(cur, line, d + " " + in_quotes(type));
      require_options(line, d);
      for (const PbrtParam& p : ps.params()) p.used = true;
      return warn(line, d,
                  "the same image either way: Kiln traces rays through Embree (or its own BVH, --accel bvh)");
    }
    if (d == "ColorSpace") {
      const std::string name = read_string(cur, line, d);
      if (name != "srgb") {
        warn(line, d, "colour space " + in_quotes(name) + " is not supported; RGB values are read as sRGB");
        diag_.unsupported("pbrt colour spaces other than srgb");
      }
      return;
    }
    if (d == "Option") {
      const std::string name = read_string(cur, line, d);
      next_token(cur, line, d);
      warn(line, d, "option " + in_quotes(name) + " is ignored");
      return diag_.unsupported("pbrt Option " + in_quotes(name), LoadOutcome::Ignored);
    }
    if (d == "WorldBegin") return world_begin(line);
    if (d == "WorldEnd") {
      require_world(line, d);
      return warn(line, d, "WorldEnd is pbrt-v3 syntax (pbrt-v4 ends the world at the end of the file); skipped");
    }
    if (d == "Attribute") return attribute(cur, line);
    if (d == "Shape") return shape(cur, line);
    if (d == "Material") {
      const std::string type = read_string(cur, line, d);
      PbrtParams ps = read_params(cur, line, d + " " + in_quotes(type), gs_.defaults.material);
      require_world(line, d);
      gs_.material = builder_.make_material(type, ps);
      return;
    }
    if (d == "MakeNamedMaterial") {
      const std::string name = read_string(cur, line, d);
      PbrtParams ps = read_params(cur, line, d + " " + in_quotes(name), gs_.defaults.material);
      require_world(line, d);
      return builder_.make_named_material(name, ps);
    }
    if (d == "NamedMaterial") {
      const std::string name = read_string(cur, line, d);
      require_world(line, d);
      gs_.material = builder_.use_named_material(name, file(), line);
      return;
    }
    if (d == "Texture") {
      const std::string name = read_string(cur, line, d);
      const std::string type = read_string(cur, line, d);
      const std::string cls = read_string(cur, line, d);
      PbrtParams ps = read_params(cur, line, d + " " + in_quotes(name), gs_.defaults.texture);
      require_world(line, d);
      return builder_.make_texture(name, type, cls, ps, gs_.ctm[0]);
    }
    if (d == "LightSource") {
      const std::string type = read_string(cur, line, d);
      PbrtParams ps = read_params(cur, line, d + " " + in_quotes(type), gs_.defaults.light);
      require_world(line, d);
      if (!same(gs_.ctm[0], gs_.ctm[1]))
        warn(line, d, "the light's transform moves over the shutter; it is lit from its start transform (as pbrt does)");
      return builder_.make_light(type, ps, gs_.ctm[0]);
    }
    if (d == "AreaLightSource") {
      const std::string type = read_string(cur, line, d);
      PbrtParams ps = read_params(cur, line, d + " " + in_quotes(type), gs_.defaults.light);
      require_world(line, d);
      gs_.area_light = builder_.make_area_light(type, ps);
      return;
    }
    if (d == "ObjectBegin") {
      const std::string name = read_string(cur, line, d);
      require_world(line, d);
      if (current_object_) fail(line, d, "ObjectBegin inside the definition of object " + in_quotes(*current_object_));
      if (objects_.count(name)) fail(line, d, "object " + in_quotes(name) + " is defined twice");
      attribute_begin(line, BlockKind::Object);
      current_object_ = name;
      objects_[name];
      return;
    }
    if (d == "ObjectEnd") {
      if (!current_object_) fail(line, d, "ObjectEnd without ObjectBegin");
      attribute_end(line, BlockKind::Object, d);
      current_object_.reset();
      return;
    }
    if (d == "ObjectInstance") return object_instance(read_string(cur, line, d), line);
    if (d == "MakeNamedMedium") {
      const std::string name = read_string(cur, line, d);
      PbrtParams ps = read_params(cur, line, d + " " + in_quotes(name), gs_.defaults.medium);
      if (!same(gs_.ctm[0], gs_.ctm[1]))
        warn(line, d, "the medium's transform moves over the shutter; it is placed at its start transform (as pbrt-v4 does)");
      return builder_.make_medium(name, ps, gs_.ctm[0],
                                  [&](const std::string& file_name, int l) { return resolve(file_name, l, ps.context()); });
    }
    if (d == "MediumInterface") {
      // One name puts the same medium on both sides (no transition).
      const std::string inside = read_string(cur, line, d);
      std::string outside = inside;
      if (const auto second = cur.peek(); second && second->kind == PbrtTokenKind::String)
        outside = read_string(cur, line, d);
      gs_.media = {medium_ref(inside, line), medium_ref(outside, line)};
      return;
    }
    fail(line, "", "unknown directive '" + std::string(t.text.substr(0, 40)) + "'");
  }

  // ---- blocks ----

  void require_world(int line, const std::string& d) const {
    if (!world_) fail(line, d, d + " before WorldBegin: shapes, lights and materials belong in the world block");
  }
  void require_options(int line, const std::string& d) const {
    if (world_) fail(line, d, d + " after WorldBegin: rendering options must come before the world block");
  }

  void attribute_begin(int line, BlockKind kind) { blocks_.push_back(Block{gs_, kind, file(), line}); }

  void attribute_end(int line, BlockKind kind, const std::string& d) {
    const bool import_floor =
        !files_.empty() && files_.back().import_blocks && blocks_.size() <= *files_.back().import_blocks + 1;
    if (blocks_.empty() || import_floor)
      fail(line, d, d + " without a matching " + (kind == BlockKind::Object ? "ObjectBegin" : "AttributeBegin"));
    const Block& b = blocks_.back();
    if (b.kind != kind)
      fail(line, d,
           d + " closes the " + (b.kind == BlockKind::Object ? "ObjectBegin" : "AttributeBegin") + " of " + b.file +
               ": line " + std::to_string(b.line));
    gs_ = b.saved;
    blocks_.pop_back();
  }

  void attribute(PbrtCursor& cur, int line) {
    const std::string target = read_string(cur, line, "Attribute");
    PbrtParams ps = read_params(cur, line, "Attribute " + in_quotes(target));
    std::shared_ptr<const PbrtParams>* slot = nullptr;
    if (target == "shape")
      slot = &gs_.defaults.shape;
    else if (target == "light")
      slot = &gs_.defaults.light;
    else if (target == "material")
      slot = &gs_.defaults.material;
    else if (target == "texture")
      slot = &gs_.defaults.texture;
    else if (target == "medium")
      slot = &gs_.defaults.medium;
    else {
      fail(line, "Attribute", "unknown target " + in_quotes(target) + " (shape, light, material, medium, texture)");
    }
    // The new values first, then the earlier defaults they do not replace.
    auto merged = std::make_shared<PbrtParams>(ps.file(), ps.context(), line);
    for (const PbrtParam& p : ps.params()) {
      p.used = true;
      merged->add(p);
    }
    if (*slot)
      for (const PbrtParam& p : (*slot)->params())
        if (!ps.has(p.name)) merged->add(p);
    for (const PbrtParam& p : merged->params()) p.used = false;
    *slot = merged;
  }

  // ---- transforms ----

  template <typename F>
  Transform checked(int line, const std::string& d, F&& make) {
    Transform t;
    try {
      t = make();
    } catch (const Error& e) {
      fail(line, d, e.what());
    }
    if (!finite_transform(t)) fail(line, d, "the transformation is not finite in single precision");
    return t;
  }

  template <typename F>
  void apply(int line, const std::string& d, F&& make) {
    const Transform x = checked(line, d, make);
    for (int i = 0; i < 2; ++i)
      if (gs_.active[size_t(i)]) {
        gs_.ctm[size_t(i)] = gs_.ctm[size_t(i)] * x;
        if (!finite_transform(gs_.ctm[size_t(i)]))
          fail(line, d, "the accumulated transformation overflows single precision");
      }
  }

  void set_ctm(int, const std::string&, const TransformPair& t) {
    for (int i = 0; i < 2; ++i)
      if (gs_.active[size_t(i)]) gs_.ctm[size_t(i)] = t[size_t(i)];
  }

  // pbrt's LookAt: the camera-from-world transform of an eye at `eye` looking at `look` (camera +z forward, +y up,
  // +x = up x forward).
  Transform look_at(Vec3f eye, Vec3f look, Vec3f up, int line) {
    const Vec3f dir = look - eye;
    if (!(length(dir) > 0.0f)) fail(line, "LookAt", "the eye and the look-at point coincide");
    const Vec3f f = normalize(dir);
    if (!(length(up) > 0.0f)) fail(line, "LookAt", "the up vector is zero");
    const Vec3f r0 = cross(normalize(up), f);
    if (!(length(r0) > 1e-6f)) fail(line, "LookAt", "the up vector is parallel to the viewing direction");
    const Vec3f r = normalize(r0);
    const Vec3f u = cross(f, r);
    Mat4 world_from_camera = Mat4::identity();
    for (int i = 0; i < 3; ++i) {
      world_from_camera.m[size_t(i)][0] = r[i];
      world_from_camera.m[size_t(i)][1] = u[i];
      world_from_camera.m[size_t(i)][2] = f[i];
      world_from_camera.m[size_t(i)][3] = eye[i];
    }
    return Transform::from_matrix(world_from_camera).inverse();
  }

  // ---- files ----

  void include(PbrtCursor& cur, int line, const std::string& d) {
    const std::string name = read_string(cur, line, d);
    const bool import = d == "Import";
    if (import) require_world(line, d);
    std::string path;
    try {
      path = resolve(name, line, d);
    } catch (const Error&) {
      if (!diag_.allow_missing_files) throw;
      diag_.missing_file(file(), line, d, "included file " + in_quotes(name) + " is missing");
      // Parameters that go on after the Include belong to the missing file's last directive: left out with it.
      PbrtParams rest(file(), d, line, files_.back().dir);
      rest.parse(cur);
      return;
    }
    std::string text;
    try {
      text = read_file_maybe_gzip(path);
    } catch (const Error& e) {
      fail(line, d, std::string("cannot read ") + in_quotes(name) + ": " + e.what());
    }
    std::optional<size_t> import_blocks;
    if (import) {
      import_blocks = blocks_.size();
      attribute_begin(line, BlockKind::Import);
    }
    std::string dir = fs::path(path).parent_path().string();
    push_file(std::move(text), path, dir.empty() ? "." : dir, line, import_blocks);
  }

  // ---- rendering options ----

  void option(PbrtCursor& cur, int line, const std::string& d) {
    const std::string type = read_string(cur, line, d);
    PbrtParams ps = read_params(cur, line, d + " " + in_quotes(type));
    require_options(line, d);
    if (d == "Camera") {
      if (have_camera_) warn(line, d, "a second Camera replaces the first");
      have_camera_ = true;
      camera_.camera_type = type;
      camera_.camera = std::move(ps);
      camera_.camera_from_world = gs_.ctm[0];
      camera_.camera_from_world_end.reset();
      if (!same(gs_.ctm[0], gs_.ctm[1])) camera_.camera_from_world_end = gs_.ctm[1];
      camera_.transform_start_time = gs_.transform_start;
      camera_.transform_end_time = gs_.transform_end;
      camera_.resolve = [this, dir = files_.back().dir, f = file()](const std::string& name, int l) {
        return resolve_in(dir, f, name, l, "Camera");
      };
      camera_medium_ = gs_.media.outside;  // pbrt-v4: the camera sits in the current "outside" medium
      coord_systems_["camera"] = {gs_.ctm[0].inverse(), gs_.ctm[1].inverse()};
    } else if (d == "Film") {
      camera_.film_type = type;
      camera_.film = std::move(ps);
    } else if (d == "Sampler") {
      camera_.sampler_type = type;
      camera_.sampler = std::move(ps);
      camera_.has_sampler = true;
    } else {
      camera_.filter_type = type;
      camera_.filter = std::move(ps);
      camera_.has_filter = true;
    }
  }

  void integrator(PbrtCursor& cur, int line) {
    const std::string type = read_string(cur, line, "Integrator");
    PbrtParams ps = read_params(cur, line, "Integrator " + in_quotes(type));
    require_options(line, "Integrator");
    if (type != "path" && type != "volpath") {
      diag_.warn(ps, "integrator " + in_quotes(type) + " is rendered with Kiln's path tracer (MIS, roulette)");
      diag_.unsupported("pbrt integrator " + in_quotes(type) + " (Kiln's path tracer renders it)");
    }
    integrator_ = type;
    integrator_file_ = file();
    integrator_line_ = line;
    const int depth = ps.get_int("maxdepth", kPbrtDefaultMaxDepth);
    if (depth < 0) ps.fail(line, "\"maxdepth\" must not be negative");
    scene_.max_recursion_depth = depth;
    if (ps.has("regularize") && ps.get_bool("regularize", false)) {
      diag_.warn(ps, "\"regularize\" is ignored (Kiln does not regularize near-specular paths)");
      diag_.unsupported("pbrt path regularization (\"regularize\")", LoadOutcome::Ignored);
    }
    if (const auto ls = ps.find_string("lightsampler"); ls && *ls != "power")
      diag_.warn(ps, "light sampler " + in_quotes(*ls) + ": Kiln chooses lights in proportion to their power");
    diag_.report_unused(ps);
  }

  void world_begin(int line) {
    if (world_) fail(line, "WorldBegin", "WorldBegin appears twice");
    if (!camera_.resolve)
      camera_.resolve = [this](const std::string& name, int l) { return resolve(name, l, "Camera"); };
    PbrtCamera c = make_pbrt_camera(camera_, diag_);
    c.desc.medium = camera_medium_;
    for (const PbrtParams* ps : {&camera_.camera, &camera_.film, &camera_.sampler, &camera_.filter})
      diag_.report_unused(*ps);
    scene_.cameras.push_back(std::move(c.desc));
    shutter_ = c.shutter;
    world_ = true;
    gs_.ctm = {Transform(), Transform()};
    gs_.active = {true, true};
    coord_systems_["world"] = gs_.ctm;
  }

  // The motion of a shape or instance whose transform moves over the shutter, checked as Kiln will use it; empty
  // when it does not move.
  std::optional<TransformMotionDesc> motion_of(const Transform& start, const Transform& end, int line,
                                               const std::string& context) {
    if (same(start, end)) return std::nullopt;
    TransformMotionDesc m{end, shutter_.to_kiln(gs_.transform_start), shutter_.to_kiln(gs_.transform_end)};
    try {
      AnimatedTransform(start, m.start_time, m.end, m.end_time);
    } catch (const Error& e) {
      fail(line, context, std::string("the transform moves over the shutter but cannot be interpolated: ") + e.what());
    }
    return m;
  }

  void finish() {
    include_trace_.clear();  // every file is closed: errors from here on name their own file and line
    builder_.resolve_mixes();
    const std::string end = "line " + std::to_string(root_end_line_);
    if (current_object_)
      throw Error(root_path_, end,
                  "the file ends inside ObjectBegin " + in_quotes(*current_object_) + " (no ObjectEnd)");
    if (!world_)
      throw Error(root_path_, end, "missing WorldBegin: the file ends before the world block (no shapes or lights)");
    for (const Block& b : blocks_)
      diag_.warn(b.file, b.line, "AttributeBegin", "has no matching AttributeEnd before the end of the scene");
    builder_.finish_named_materials();
    resolve_media();
  }

  // ---- media ----

  // A reference to a medium by name, -1 for none ("").
  int medium_ref(const std::string& name, int line) {
    if (name.empty()) return -1;
    medium_refs_.push_back({name, file(), line});
    return int(medium_refs_.size()) - 1;
  }

  // A name no MakeNamedMedium defines is an error, or under allow_missing_files (its definition may be in a missing
  // file) vacuum, reported.
  int resolve_medium(int ref) {
    if (ref < 0) return -1;
    const MediumRef& r = medium_refs_[size_t(ref)];
    if (const auto m = builder_.named_medium(r.name)) return *m;
    if (!diag_.allow_missing_files)
      throw Error(r.file, location(r.line, "MediumInterface"),
                  "no medium named " + in_quotes(r.name) + " (MakeNamedMedium defines them)");
    diag_.warn(r.file, r.line, "MediumInterface",
               "no medium named " + in_quotes(r.name) + " is defined (in a missing file?); vacuum is used");
    diag_.unsupported("media defined nowhere (left out: --allow-missing)");
    return -1;
  }

  void resolve_media() {
    const auto resolve_interface = [&](MediumInterfaceDesc& mi) {
      mi = {resolve_medium(mi.inside), resolve_medium(mi.outside)};
    };
    for (MeshDesc& m : scene_.meshes) resolve_interface(m.media);
    for (SphereDesc& sp : scene_.spheres) resolve_interface(sp.media);
    for (InstanceDesc& inst : scene_.instances) resolve_interface(inst.media);
    for (QuadricDesc& q : scene_.quadrics) resolve_interface(q.media);
    for (CameraDesc& c : scene_.cameras) c.medium = resolve_medium(c.medium);
    if (!scene_.media.empty() && integrator_ == "path")
      diag_.warn(integrator_file_, integrator_line_, "Integrator",
                 "pbrt-v4's \"path\" integrator ignores participating media; Kiln renders them (volumetric path "
                 "tracing)");
  }

  // ---- shapes ----

  void shape(PbrtCursor& cur, int line) {
    const std::string type = read_string(cur, line, "Shape");
    PbrtParams ps = read_params(cur, line, "Shape " + in_quotes(type), gs_.defaults.shape);
    require_world(line, "Shape");
    const PbrtShapeContext ctx{diag_, [&](const std::string& name, int l) { return resolve(name, l, ps.context()); },
                               [&](const PbrtParams& p) { return builder_.shape_alpha(p); }};
    PbrtShape s = make_pbrt_shape(type, ps, ctx);
    diag_.report_unused(ps);
    if (s.empty()) return;
    const Transform& to_world = gs_.ctm[0];
    const bool flipped = gs_.reverse_orientation != to_world.swaps_handedness();
    std::optional<PbrtAreaLight> light = gs_.area_light;
    if (light && current_object_) {
      warn(line, ps.context(), "area lights inside ObjectBegin are not supported (pbrt-v4 ignores them too)");
      light.reset();
    }
    const std::optional<TransformMotionDesc> motion = shape_motion(line, ps.context(), light.has_value());
    const int material = gs_.material >= 0 ? gs_.material : builder_.default_material(file());
    if (s.mesh) {
      MeshDesc& m = *s.mesh;
      m.material = material;
      m.to_world = to_world;
      m.media = gs_.media;
      orient(m, flipped, gs_.reverse_orientation);
      if (!m.normals.empty() && !to_world.invertible()) {
        warn(line, ps.context(), "the transform is singular, so the normals \"N\" cannot follow it; face normals used");
        diag_.unsupported("shading normals under a singular transform");
        m.normals.clear();
      }
      if (light) {
        m.emission = light->radiance;
        m.two_sided_emission = light->two_sided;
        m.emission_image = light->image;
        if (light->image && m.uvs.empty()) m.uvs = std::move(s.patch_uvs);
      }
      if (current_object_) {
        m.visible = false;
        objects_[*current_object_].meshes.push_back(int(scene_.meshes.size()));
      }
      if (motion) return moving_mesh(std::move(m), *motion);
      scene_.meshes.push_back(std::move(m));
      return;
    }
    if (s.quadric) {
      QuadricDesc& q = *s.quadric;
      q.material = material;
      q.to_world = to_world;
      q.to_world_motion = motion;
      q.flip = flipped;
      q.media = gs_.media;  // the quadric's normal is pbrt's (flip included), so its sides are pbrt's
      if (light) {
        q.emission = light->radiance;
        q.two_sided_emission = light->two_sided;
        q.emission_image = light->image;
      }
      (current_object_ ? objects_[*current_object_].quadrics : scene_.quadrics).push_back(q);
      return;
    }
    if (light && light->image) {  // a whole-turn quadric sphere: pbrt's (u, v) for the image, both sides
      QuadricDesc q = quadric_of_sphere(*s.sphere);
      q.material = material;
      q.to_world = to_world * Transform::translate(s.sphere->center);
      q.flip = flipped;
      q.media = gs_.media;
      q.emission = light->radiance;
      q.two_sided_emission = light->two_sided;
      q.emission_image = light->image;
      scene_.quadrics.push_back(q);
      return;
    }
    SphereDesc sp = *s.sphere;
    sp.material = material;
    sp.to_world = to_world;
    sp.to_world_motion = motion;
    if (!to_world.invertible()) fail(line, ps.context(), "the transform is singular: a sphere needs its inverse");
    // Kiln's sphere normal always points out of the sphere; pbrt's "outside" is where its normal points.
    sp.media = flipped ? MediumInterfaceDesc{gs_.media.outside, gs_.media.inside} : gs_.media;
    if (light) {
      if (flipped) {
        warn(line, ps.context(),
             "a sphere light facing inwards (ReverseOrientation) is not supported; it does not emit");
        diag_.unsupported("inward-facing sphere lights", LoadOutcome::Ignored);
      } else {
        sp.emission = light->radiance;
        if (light->two_sided) {
          warn(line, ps.context(), "a two-sided sphere light emits only outwards in Kiln (its inside is dark)");
          diag_.unsupported("two-sided sphere lights (the inside is dark)");
        }
      }
    }
    if (current_object_)
      objects_[*current_object_].spheres.push_back(sp);
    else
      scene_.spheres.push_back(sp);
  }

  // The shape's motion when its transform moves over the shutter. Kiln does not move emitters (their light samples
  // would not follow) nor shapes inside an object definition (instances move as a whole): those stay at the start.
  std::optional<TransformMotionDesc> shape_motion(int line, const std::string& context, bool emits) {
    if (same(gs_.ctm[0], gs_.ctm[1])) return std::nullopt;
    if (emits || current_object_) {
      warn(line, context,
           std::string("the transform moves over the shutter, but Kiln does not move ") +
               (emits ? "area lights" : "shapes inside ObjectBegin (move the ObjectInstance)") +
               "; it is rendered at its start transform");
      diag_.unsupported(emits ? "moving area lights (pbrt ActiveTransform on an emitter)"
                              : "moving shapes inside object definitions (pbrt ActiveTransform in ObjectBegin)");
      return std::nullopt;
    }
    return motion_of(gs_.ctm[0], gs_.ctm[1], line, context);
  }

  // A moving mesh is rendered as an instance of its object-space self whose transform moves.
  void moving_mesh(MeshDesc m, const TransformMotionDesc& motion) {
    m.visible = false;
    m.is_instance_base = true;
    InstanceDesc inst;
    inst.name = m.name;
    inst.base_mesh = int(scene_.meshes.size());
    inst.to_world = m.to_world;
    inst.to_world_motion = motion;
    inst.material = m.material;
    scene_.meshes.push_back(std::move(m));
    scene_.instances.push_back(std::move(inst));
  }

  // pbrt's emitting (and refracting) side: the side of the shading normals "N" when the mesh has them (negated by
  // ReverseOrientation), else the winding order's side flipped by ReverseOrientation and by a mirroring transform.
  // Kiln's side is always the world-space winding, so triangles are re-wound to match.
  static void orient(MeshDesc& m, bool flipped, bool reverse) {
    const size_t tris = m.indices.size() / 3;
    if (m.normals.empty()) {
      if (flipped)
        for (size_t t = 0; t < tris; ++t) std::swap(m.indices[3 * t + 1], m.indices[3 * t + 2]);
      return;
    }
    if (reverse)
      for (Vec3f& n : m.normals) n = -n;
    for (size_t t = 0; t < tris; ++t) {
      uint32_t* v = &m.indices[3 * t];
      const Vec3f p0 = m.to_world.point(m.positions[v[0]]), p1 = m.to_world.point(m.positions[v[1]]),
                  p2 = m.to_world.point(m.positions[v[2]]);
      const Vec3f n = m.to_world.normal(m.normals[v[0]] + m.normals[v[1]] + m.normals[v[2]]);
      if (dot(cross(p1 - p0, p2 - p0), n) < 0.0f) std::swap(v[1], v[2]);
    }
  }

  void object_instance(const std::string& name, int line) {
    require_world(line, "ObjectInstance");
    if (current_object_)
      fail(line, "ObjectInstance", "ObjectInstance inside the definition of object " + in_quotes(*current_object_));
    const auto it = objects_.find(name);
    if (it == objects_.end())
      fail(line, "ObjectInstance", "no object named " + in_quotes(name) + " (ObjectBegin defines them)");
    const Transform& placement = gs_.ctm[0];
    if (!placement.invertible())
      fail(line, "ObjectInstance", "the instance transform is singular: Kiln traces instances through its inverse");
    const std::string label = "ObjectInstance " + in_quotes(name) + " (" + fs::path(file()).filename().string() + ":" +
                              std::to_string(line) + ")";
    // A moving placement moves every shape of the object with it.
    const auto moved = [&](const Transform& object_to_world) -> std::optional<TransformMotionDesc> {
      if (same(gs_.ctm[0], gs_.ctm[1])) return std::nullopt;
      return motion_of(placement * object_to_world, gs_.ctm[1] * object_to_world, line, "ObjectInstance");
    };
    for (int mi : it->second.meshes) {
      MeshDesc& base = scene_.meshes[size_t(mi)];
      base.is_instance_base = true;
      InstanceDesc inst;
      inst.name = label;
      inst.base_mesh = mi;
      inst.to_world = placement * base.to_world;
      if (!finite_transform(inst.to_world) || !inst.to_world.invertible())
        fail(line, "ObjectInstance", "the instance transform overflows single precision or is singular");
      inst.to_world_motion = moved(base.to_world);
      inst.material = base.material;
      inst.media = base.media;
      scene_.instances.push_back(inst);
    }
    for (SphereDesc s : it->second.spheres) {
      s.to_world_motion = moved(s.to_world);
      s.to_world = placement * s.to_world;
      s.name = label + " " + s.name;
      scene_.spheres.push_back(s);
    }
    for (QuadricDesc q : it->second.quadrics) {
      q.to_world_motion = moved(q.to_world);
      q.to_world = placement * q.to_world;
      q.name = label + " " + q.name;
      scene_.quadrics.push_back(q);
    }
  }

  // ---- state ----

  SceneDesc scene_;
  PbrtBuilder builder_{scene_, [this](const std::string& name, const PbrtParams& ps) {
                         return resolve(name, ps.line(), ps.context());
                       }};
  PbrtDiagnostics& diag_ = builder_.diagnostics();
  std::string root_path_, root_dir_, include_trace_;
  std::vector<OpenFile> files_;
  GraphicsState gs_;
  std::vector<Block> blocks_;
  PbrtShutter shutter_;
  bool world_ = false, have_camera_ = false, warned_transform_block_ = false;
  PbrtCameraInput camera_;
  std::map<std::string, TransformPair> coord_systems_;
  std::map<std::string, ObjectDef> objects_;
  std::optional<std::string> current_object_;
  int root_end_line_ = 0;
  struct MediumRef {
    std::string name, file;
    int line = 0;
  };
  std::vector<MediumRef> medium_refs_;
  int camera_medium_ = -1;  // a reference into medium_refs_ until the file ends
  std::string integrator_, integrator_file_;
  int integrator_line_ = 0;
};

}  // namespace

SceneDesc parse_pbrt(std::string text, const std::string& path, const PbrtOptions& options) {
  return PbrtParser(path, options).run(std::move(text));
}

SceneDesc load_pbrt(const std::string& path, const PbrtOptions& options) {
  return parse_pbrt(read_file_maybe_gzip(path), path, options);
}

}  // namespace kiln
