#include "scenes/xml_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <pugixml.hpp>
#include <unordered_map>
#include <unordered_set>

#include "core/error.h"
#include "scenes/parse_util.h"
#include "scenes/ply_loader.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using Node = pugi::xml_node;

constexpr uint32_t kUnmapped = std::numeric_limits<uint32_t>::max();
// Face indices beyond this magnitude cannot name a vertex; offsets are ints, so index arithmetic stays in int64.
constexpr int64_t kMaxListedIndex = int64_t(1) << 62;
constexpr float kMaxFovYDeg = 180.0f;
constexpr float kMaxConeAngleDeg = 180.0f;
constexpr float kMaxBurnPercent = 100.0f;

// Elements each container understands; anything else is reported in SceneDesc::warnings and skipped.
// clang-format off
const std::initializer_list<std::string_view> kSceneChildren = {
    "MaxRecursionDepth", "BackgroundColor", "ShadowRayEpsilon", "IntersectionTestEpsilon", "ZeroBasedIndexing",
    "Cameras", "Camera", "Lights", "BRDFs", "Materials", "Transformations", "VertexData", "TexCoordData", "Textures",
    "Objects", "BackgroundTexture", "BackfaceCulling", "Integrator", "IntegratorParams"};
const std::initializer_list<std::string_view> kCameraChildren = {
    "Position", "Gaze", "GazePoint", "Up", "NearPlane", "NearDistance", "FovY", "ImageResolution", "ImageName",
    "NumSamples", "FocusDistance", "ApertureSize", "Tonemap", "Renderer", "RendererParams", "GammaCorrection"};
const std::initializer_list<std::string_view> kMaterialChildren = {
    "AmbientReflectance", "DiffuseReflectance", "SpecularReflectance", "MirrorReflectance", "PhongExponent",
    "Roughness", "Transparency", "RefractionIndex", "AbsorptionCoefficient", "AbsorptionIndex"};
// clang-format on

struct BrdfKindName {
  std::string_view name;
  BrdfKind kind;
};
constexpr BrdfKindName kBrdfKinds[] = {{"OriginalPhong", BrdfKind::OriginalPhong},
                                       {"ModifiedPhong", BrdfKind::ModifiedPhong},
                                       {"OriginalBlinnPhong", BrdfKind::OriginalBlinnPhong},
                                       {"ModifiedBlinnPhong", BrdfKind::ModifiedBlinnPhong},
                                       {"TorranceSparrow", BrdfKind::TorranceSparrow}};

// Transformation kinds and their token letters: t, s, r, c.
enum XformKind { kTranslation, kScaling, kRotation, kComposite, kXformKinds };
constexpr std::string_view kXformElement[kXformKinds] = {"Translation", "Scaling", "Rotation", "Composite"};
constexpr char kXformLetter[kXformKinds] = {'t', 's', 'r', 'c'};

uint32_t le_u32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}
float le_f32(const char* p) {
  const uint32_t u = le_u32(p);
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

// False when the matrix or its inverse overflowed single precision (a denormal scale factor, a product of large
// factors): every point it maps would be inf or NaN.
bool transform_is_finite(const Transform& t) {
  for (const Mat4* m : {&t.matrix(), &t.inverse_matrix()})
    for (const auto& row : m->m)
      for (float x : row)
        if (!std::isfinite(x)) return false;
  return true;
}

class XmlLoader {
 public:
  explicit XmlLoader(const std::string& path) : file_(path), dir_(fs::path(path).parent_path()) {}

  SceneDesc load() {
    text_ = read_file_bytes(file_);
    line_starts_.push_back(0);
    for (size_t i = 0; i < text_.size(); ++i)
      if (text_[i] == '\n') line_starts_.push_back(i + 1);

    pugi::xml_document doc;
    const auto res = doc.load_buffer(text_.data(), text_.size(), pugi::parse_default, pugi::encoding_auto);
    if (!res)
      throw Error(file_, "line " + std::to_string(line_at(size_t(std::max<ptrdiff_t>(res.offset, 0)))),
                  std::string("malformed XML: ") + res.description());
    root_ = doc.document_element();
    if (!root_) throw Error(file_, "", "no root element (expected <Scene>)");
    if (std::string_view(root_.name()) != "Scene")
      fail(root_, "root element is <" + std::string(root_.name()) + ">, expected <Scene>");

    scene_.source_path = file_;
    scene_.format = "ceng795-xml";
    scene_.rules = read_rules(root_);
    warn_unknown_children(root_, kSceneChildren);
    // Fixed processing order: the files do not order their top-level elements consistently.
    read_globals();
    for (Node n : root_.children("VertexData")) read_vertex_data(n);
    for (Node n : root_.children("TexCoordData")) read_texcoord_data(n);
    for (Node n : root_.children("Transformations")) read_transformations(n);
    for (Node n : root_.children("BRDFs")) read_brdfs(n);
    for (Node n : root_.children("Materials")) read_materials(n);
    for (Node n : root_.children("Textures")) read_textures(n);
    for (Node n : root_.children("Cameras")) {
      warn_unknown_children(n, {"Camera"});
      for (Node c : n.children("Camera")) read_camera(c);
    }
    for (Node c : root_.children("Camera")) read_camera(c);  // 2017: no <Cameras> wrapper
    read_scene_integrator();
    for (Node n : root_.children("Lights")) read_lights(n);
    for (Node n : root_.children("Objects")) read_objects(n);
    for (Node n : root_.children("Objects"))
      for (Node c : n.children("MeshInstance")) read_instance(c);
    return std::move(scene_);
  }

 private:
  // ---- locations, messages ------------------------------------------------------------------------------------
  int line_at(size_t offset) const {
    return int(std::upper_bound(line_starts_.begin(), line_starts_.end(), offset) - line_starts_.begin());
  }
  int line_of(Node n) const {
    const ptrdiff_t off = n.offset_debug();
    return off < 0 ? 0 : line_at(size_t(off));
  }
  std::string path_of(Node n) const {
    std::vector<std::string> parts;
    for (; n && n.type() == pugi::node_element && n != root_; n = n.parent()) {
      std::string s = n.name();
      if (auto id = n.attribute("id")) s += std::string(" id=") + std::string(trim(id.value()));
      parts.push_back(std::move(s));
    }
    if (parts.empty()) return "Scene";
    std::string out;
    for (auto it = parts.rbegin(); it != parts.rend(); ++it) out += (out.empty() ? "" : " / ") + *it;
    return out;
  }
  std::string location(Node n) const {
    const int l = line_of(n);
    return (l > 0 ? "line " + std::to_string(l) + " (" : "(") + path_of(n) + ")";
  }
  [[noreturn]] void fail(Node n, const std::string& message) const { throw Error(file_, location(n), message); }
  void warn(Node n, const std::string& message) {
    scene_.warnings.push_back(Error::format(file_, location(n), message));
  }

  void warn_unknown_children(Node n, std::initializer_list<std::string_view> known) {
    for (Node c : n.children()) {
      if (c.type() != pugi::node_element) continue;  // stray text (e.g. a dangling "-->") and comments are ignored
      if (std::find(known.begin(), known.end(), std::string_view(c.name())) == known.end())
        warn(c, "unknown element <" + std::string(c.name()) + "> ignored");
    }
  }

  // ---- text and children --------------------------------------------------------------------------------------
  // All character data of an element (comments inside a value are skipped).
  static std::string text_of(Node n) {
    std::string s;
    for (Node c : n.children())
      if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) {
        if (!s.empty()) s += ' ';
        s += c.value();
      }
    return s;
  }
  TextSource source(Node n) const {
    Node first_text = n;
    for (Node c : n.children())
      if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) {
        first_text = c;
        break;
      }
    return {file_, line_of(first_text), path_of(n)};
  }
  Node opt_child(Node n, const char* name) const {
    Node found;
    for (Node c : n.children(name)) {
      if (found) fail(c, std::string("duplicate <") + name + ">");
      found = c;
    }
    return found;
  }
  Node req_child(Node n, const char* name) const {
    Node c = opt_child(n, name);
    if (!c) fail(n, std::string("missing <") + name + ">");
    return c;
  }
  float get_float(Node n) const { return parse_float(text_of(n), source(n)); }
  int get_int(Node n) const { return parse_int(text_of(n), source(n)); }
  bool get_bool(Node n) const { return parse_bool(text_of(n), source(n)); }
  Vec3f get_vec3(Node n) const { return parse_vec3(text_of(n), source(n)); }
  Rgb get_rgb(Node n) const { return parse_rgb(text_of(n), source(n)); }
  std::string get_string(Node n) const {
    const std::string s(trim(text_of(n)));
    if (s.empty()) fail(n, "is empty");
    return s;
  }
  float positive(Node n, float v, const char* what) const {
    if (!(v > 0.0f)) fail(n, std::string(what) + " must be positive, got " + std::to_string(v));
    return v;
  }
  float non_negative(Node n, float v, const char* what) const {
    if (v < 0.0f) fail(n, std::string(what) + " must not be negative, got " + std::to_string(v));
    return v;
  }

  // ---- attributes ---------------------------------------------------------------------------------------------
  std::optional<std::string> attr(Node n, const char* name) const {
    const auto a = n.attribute(name);
    if (!a) return std::nullopt;
    return std::string(trim(a.value()));
  }
  TextSource attr_source(Node n, const char* name) const { return {file_, line_of(n), path_of(n) + " @" + name}; }
  int int_attr(Node n, const char* name, int fallback) const {
    const auto v = attr(n, name);
    return v ? parse_int(*v, attr_source(n, name)) : fallback;
  }
  bool bool_attr(Node n, const char* name, bool fallback) const {
    const auto v = attr(n, name);
    return v ? parse_bool(*v, attr_source(n, name)) : fallback;
  }
  int id_of(Node n) const {
    if (!n.attribute("id")) fail(n, "missing id attribute");
    return int_attr(n, "id", 0);
  }
  std::string resolve(const std::string& rel) const {
    const fs::path p(rel);
    return (p.is_absolute() ? p : dir_ / p).lexically_normal().string();
  }
  // A file the render reads besides the ones read here (a texture image, an environment map) joins the scene's
  // identity (SceneDesc::external_files). Returns the path.
  std::string uses_file(const std::string& path) {
    scene_.external_files.push_back(path);
    return path;
  }

  // ---- top-level scalars ---------------------------------------------------------------------------------------
  void read_globals() {
    if (Node n = opt_child(root_, "ZeroBasedIndexing")) zero_based_ = get_bool(n);
    if (Node n = opt_child(root_, "BackgroundColor")) scene_.background = get_rgb(n);
    if (Node n = opt_child(root_, "ShadowRayEpsilon"))
      scene_.shadow_ray_epsilon = non_negative(n, get_float(n), "ShadowRayEpsilon");
    if (Node n = opt_child(root_, "IntersectionTestEpsilon"))
      scene_.intersection_test_epsilon = non_negative(n, get_float(n), "IntersectionTestEpsilon");
    if (Node n = opt_child(root_, "MaxRecursionDepth")) {
      const int d = get_int(n);
      if (d < 0) fail(n, "MaxRecursionDepth must not be negative, got " + std::to_string(d));
      scene_.max_recursion_depth = d;
    }
    if (Node n = opt_child(root_, "BackfaceCulling")) scene_.backface_culling = get_bool(n);
    if (Node n = opt_child(root_, "BackgroundTexture")) {  // 2019: an image path
      // It has no Interpolation nor Normalizer: each pixel shows the texel under its centre, at the file's values
      // (Normalizer 1), the 0-255 scale of BackgroundColor and of the output in the course's LDR scenes, as the
      // 2019 replace_all textures give it (hw4 ellipsoids_texture). The 2021 replace_background TextureMap says
      // both itself.
      TextureDesc t;
      t.name = location(n);
      t.image_path = uses_file(resolve(get_string(n)));
      t.decal = DecalMode::ReplaceBackground;
      t.filter = TextureFilter::Nearest;
      t.normalizer = 1.0f;
      t.wrap = TextureWrap::Clamp;
      scene_.background_texture = int(scene_.textures.size());
      scene_.textures.push_back(std::move(t));
    }
  }

  // ---- vertex / texcoord data ------------------------------------------------------------------------------------
  // binaryFile layout (course 2019): little-endian int32 count N, then N * `floats` float32 values.
  std::vector<float> read_binary_floats(Node n, const std::string& rel, size_t per_entry) {
    const std::string bytes = read_referenced(n, "binaryFile", rel);
    if (bytes.size() < 4) fail(n, "binaryFile '" + rel + "' is truncated (no count)");
    const int32_t count = int32_t(le_u32(bytes.data()));
    if (count < 0) fail(n, "binaryFile '" + rel + "' has a negative count " + std::to_string(count));
    const uint64_t need = 4 + uint64_t(count) * per_entry * 4;
    if (bytes.size() < need)
      fail(n, "binaryFile '" + rel + "' is truncated: " + std::to_string(count) + " entries need " +
                  std::to_string(need) + " bytes, file has " + std::to_string(bytes.size()));
    if (bytes.size() > need) warn(n, "binaryFile '" + rel + "' has trailing bytes after its data");
    std::vector<float> out(size_t(count) * per_entry);
    for (size_t i = 0; i < out.size(); ++i) {
      out[i] = le_f32(bytes.data() + 4 + 4 * i);
      if (!std::isfinite(out[i])) fail(n, "binaryFile '" + rel + "': value #" + std::to_string(i) + " is not finite");
    }
    return out;
  }
  std::string read_referenced(Node n, const char* attr_name, const std::string& rel) const {
    try {
      return read_file_bytes(resolve(rel));
    } catch (const Error& e) {
      fail(n, std::string(attr_name) + " '" + rel + "': " + e.what());
    }
  }

  void read_vertex_data(Node n) {
    const auto bin = attr(n, "binaryFile");
    const std::vector<float> v = bin ? read_binary_floats(n, *bin, 3) : parse_floats(text_of(n), source(n));
    if (v.size() % 3 != 0) fail(n, "has " + std::to_string(v.size()) + " numbers, not a multiple of 3");
    for (size_t i = 0; i < v.size(); i += 3) vertices_.push_back({v[i], v[i + 1], v[i + 2]});
  }
  void read_texcoord_data(Node n) {
    const auto bin = attr(n, "binaryFile");
    const std::vector<float> v = bin ? read_binary_floats(n, *bin, 2) : parse_floats(text_of(n), source(n));
    if (v.size() % 2 != 0) fail(n, "has " + std::to_string(v.size()) + " numbers, not a multiple of 2");
    for (size_t i = 0; i < v.size(); i += 2) texcoords_.push_back({v[i], v[i + 1]});
  }

  // ---- transformations ---------------------------------------------------------------------------------------
  void read_transformations(Node n) {
    for (Node c : n.children()) {
      if (c.type() != pugi::node_element) continue;
      const auto* kind_it = std::find(std::begin(kXformElement), std::end(kXformElement), std::string_view(c.name()));
      if (kind_it == std::end(kXformElement)) {
        warn(c, "unknown element <" + std::string(c.name()) + "> ignored");
        continue;
      }
      const auto kind = XformKind(kind_it - std::begin(kXformElement));
      const int id = id_of(c);
      float v[16];
      const size_t count = kind == kRotation ? 4 : kind == kComposite ? 16 : 3;
      parse_floats_exact(text_of(c), std::span<float>(v, count), source(c));
      Transform t;
      try {  // the constructors reject singular transforms (zero scale, zero axis, singular matrix)
        if (kind == kTranslation) {
          t = Transform::translate({v[0], v[1], v[2]});
        } else if (kind == kScaling) {
          t = Transform::scale({v[0], v[1], v[2]});
        } else if (kind == kRotation) {
          t = Transform::rotate(v[0], {v[1], v[2], v[3]});
        } else {
          Mat4 m;
          for (size_t i = 0; i < 16; ++i) m.m[i / 4][i % 4] = v[i];
          t = Transform::from_matrix(m);
        }
      } catch (const Error& e) {
        fail(c, e.what());
      }
      if (!transform_is_finite(t)) fail(c, "transformation or its inverse overflows single precision");
      if (!xforms_[kind].emplace(id, t).second)
        fail(c, "duplicate " + std::string(c.name()) + " id " + std::to_string(id));
    }
  }

  // M = T_last ... T_1 for the tokens "T_1 ... T_last".
  Transform object_transform(Node obj) const {
    Node n = opt_child(obj, "Transformations");
    if (!n) return {};
    Transform m;
    const std::string text = text_of(n);
    for (std::string_view tok : split_whitespace(text)) {
      const auto* letter = std::find(std::begin(kXformLetter), std::end(kXformLetter), tok.front());
      const auto id = to_int64(tok.substr(1));
      if (letter == std::end(kXformLetter) || !id)
        fail(n, "bad transformation token '" + std::string(tok) + "' (expected tN, sN, rN or cN)");
      const auto kind = size_t(letter - std::begin(kXformLetter));
      const auto it = xforms_[kind].find(int(*id));
      if (it == xforms_[kind].end())
        fail(n, "'" + std::string(tok) + "' refers to " + std::string(kXformElement[kind]) +
                    " id=" + std::to_string(*id) + ", which is not defined");
      m = it->second * m;
    }
    if (!transform_is_finite(m)) fail(n, "the composed transformation overflows single precision");
    return m;
  }

  // ---- BRDFs and materials -----------------------------------------------------------------------------------
  void read_brdfs(Node n) {
    for (Node c : n.children()) {
      if (c.type() != pugi::node_element) continue;
      const auto* k = std::find_if(std::begin(kBrdfKinds), std::end(kBrdfKinds),
                                   [&](const BrdfKindName& b) { return b.name == c.name(); });
      if (k == std::end(kBrdfKinds)) {
        warn(c, "unknown BRDF <" + std::string(c.name()) + "> ignored");
        continue;
      }
      warn_unknown_children(c, {"Exponent", "RefractiveIndex"});
      BrdfDesc b;
      b.id = id_of(c);
      b.kind = k->kind;
      b.exponent = non_negative(c, get_float(req_child(c, "Exponent")), "Exponent");
      b.normalized = bool_attr(c, "normalized", false);
      b.kd_fresnel = bool_attr(c, "kdfresnel", false);
      if (Node r = opt_child(c, "RefractiveIndex")) b.refractive_index = positive(r, get_float(r), "RefractiveIndex");
      if (!brdf_index_.emplace(b.id, int(scene_.brdfs.size())).second)
        fail(c, "duplicate BRDF id " + std::to_string(b.id) + " (BRDF ids are shared by all BRDF kinds)");
      scene_.brdfs.push_back(b);
    }
  }

  void read_materials(Node n) {
    warn_unknown_children(n, {"Material"});
    for (Node c : n.children("Material")) {
      warn_unknown_children(c, kMaterialChildren);
      MaterialDesc m;
      m.id = id_of(c);
      if (c.attribute("BRDF")) {
        const int b = int_attr(c, "BRDF", 0);
        const auto it = brdf_index_.find(b);
        if (it == brdf_index_.end()) fail(c, "BRDF " + std::to_string(b) + " is not defined");
        m.brdf = it->second;
      }
      m.degamma = bool_attr(c, "degamma", false);
      auto rgb = [&](const char* name, Rgb& out) {
        if (Node v = opt_child(c, name)) out = get_rgb(v);
      };
      rgb("AmbientReflectance", m.ambient);
      rgb("DiffuseReflectance", m.diffuse);
      rgb("SpecularReflectance", m.specular);
      rgb("MirrorReflectance", m.mirror);
      rgb("Transparency", m.transparency);
      rgb("AbsorptionCoefficient", m.absorption_coefficient);
      if (Node v = opt_child(c, "PhongExponent")) m.phong_exponent = non_negative(v, get_float(v), "PhongExponent");
      if (Node v = opt_child(c, "Roughness")) m.roughness = non_negative(v, get_float(v), "Roughness");
      if (Node v = opt_child(c, "RefractionIndex")) {
        m.refraction_index = positive(v, get_float(v), "RefractionIndex");
        m.has_refraction_index = true;
      }
      if (Node v = opt_child(c, "AbsorptionIndex"))
        m.absorption_index = non_negative(v, get_float(v), "AbsorptionIndex");
      if (const auto type = attr(c, "type")) {
        if (*type == "mirror")
          m.type = MaterialType::Mirror;
        else if (*type == "dielectric")
          m.type = MaterialType::Dielectric;
        else if (*type == "conductor")
          m.type = MaterialType::Conductor;
        else
          fail(c, "unknown material type '" + *type + "' (expected mirror, dielectric or conductor)");
      }  // no type (2019): stays Plain; build_material infers dielectric/mirror from Transparency/MirrorReflectance
      if (!material_index_.emplace(m.id, int(scene_.materials.size())).second)
        fail(c, "duplicate Material id " + std::to_string(m.id));
      scene_.materials.push_back(m);
    }
  }

  // ---- textures ----------------------------------------------------------------------------------------------
  void read_textures(Node n) {
    warn_unknown_children(n, {"Texture", "Images", "TextureMap"});
    for (Node images : n.children("Images")) {  // 2021 form: images first, texture maps refer to them by id
      warn_unknown_children(images, {"Image"});
      for (Node img : images.children("Image")) {
        const int id = id_of(img);
        if (!image_paths_.emplace(id, resolve(get_string(img))).second)
          fail(img, "duplicate Image id " + std::to_string(id));
      }
    }
    for (Node c : n.children("Texture")) read_texture_2019(c);
    for (Node c : n.children("TextureMap")) read_texture_map_2021(c);
  }

  void add_texture(Node c, TextureDesc t) {
    const int id = id_of(c);
    if (!texture_index_.emplace(id, int(scene_.textures.size())).second)
      fail(c, "duplicate texture id " + std::to_string(id));
    t.name = location(c);
    if (t.decal == DecalMode::ReplaceBackground) {
      if (scene_.background_texture) fail(c, "a second replace_background texture");
      scene_.background_texture = int(scene_.textures.size());
    }
    scene_.textures.push_back(std::move(t));
  }

  template <typename E, size_t N>
  E keyword(Node n, const std::pair<std::string_view, E> (&table)[N], const char* what) const {
    const std::string v = get_string(n);
    std::string choices;
    for (const auto& [name, value] : table) {
      if (v == name) return value;
      choices += (choices.empty() ? "" : ", ") + std::string(name);
    }
    fail(n, "unknown " + std::string(what) + " '" + v + "' (expected " + choices + ")");
  }

  // Children both forms share.
  void read_common_texture_children(Node c, TextureDesc& t) {
    // trilinear and ewa are Kiln's own (filtered over the pixel footprint), accepted in both forms.
    static constexpr std::pair<std::string_view, TextureFilter> kFilters[] = {{"nearest", TextureFilter::Nearest},
                                                                             {"bilinear", TextureFilter::Bilinear},
                                                                             {"trilinear", TextureFilter::Trilinear},
                                                                             {"ewa", TextureFilter::Ewa}};
    static constexpr std::pair<std::string_view, DecalMode> kDecals[] = {
        {"replace_kd", DecalMode::ReplaceKd},         {"blend_kd", DecalMode::BlendKd},
        {"replace_ks", DecalMode::ReplaceKs},         {"replace_all", DecalMode::ReplaceAll},
        {"replace_normal", DecalMode::ReplaceNormal}, {"bump_normal", DecalMode::BumpNormal},
        {"replace_background", DecalMode::ReplaceBackground}};
    if (Node v = opt_child(c, "Interpolation")) t.filter = keyword(v, kFilters, "Interpolation");
    if (Node v = opt_child(c, "DecalMode")) t.decal = keyword(v, kDecals, "DecalMode");
    if (Node v = opt_child(c, "Normalizer")) t.normalizer = positive(v, get_float(v), "Normalizer");
    t.degamma = bool_attr(c, "degamma", false);
    for (const char* name : {"Scale", "ScalingFactor"})
      if (Node v = opt_child(c, name)) {
        t.checker_scale = positive(v, get_float(v), name);
        t.noise_scale = t.checker_scale;
      }
    if (Node v = opt_child(c, "Offset")) t.checker_offset = get_float(v);
    if (Node v = opt_child(c, "BlackColor")) t.black = get_rgb(v);
    if (Node v = opt_child(c, "WhiteColor")) t.white = get_rgb(v);
    if (Node v = opt_child(c, "NoiseScale")) t.noise_scale = positive(v, get_float(v), "NoiseScale");
    if (Node v = opt_child(c, "BumpFactor")) t.bump_factor = get_float(v);
    if (t.decal == DecalMode::BumpNormal) t.bump = true;
  }

  // 2019: <Texture id [bumpmap] [bumpmapMultiplier] [degamma]> with ImageName (a path or perlin / checkerboard).
  void read_texture_2019(Node c) {
    warn_unknown_children(c, {"ImageName", "Interpolation", "DecalMode", "Normalizer", "Appearance", "ScalingFactor",
                              "Offset", "BlackColor", "WhiteColor", "BumpFactor", "NoiseScale", "Scale"});
    TextureDesc t;
    const std::string image = get_string(req_child(c, "ImageName"));
    t.source = image == "perlin"         ? TextureSource::Perlin
               : image == "checkerboard" ? TextureSource::Checkerboard
                                         : TextureSource::Image;
    if (t.source == TextureSource::Image) t.image_path = uses_file(resolve(image));
    read_common_texture_children(c, t);
    if (Node v = opt_child(c, "Appearance")) {
      const std::string a = get_string(v);
      if (t.source == TextureSource::Perlin && (a == "patch" || a == "vein"))
        t.noise = a == "patch" ? NoiseConversion::Linear : NoiseConversion::AbsVal;
      else if (t.source == TextureSource::Image && (a == "repeat" || a == "clamp"))
        t.wrap = a == "repeat" ? TextureWrap::Repeat : TextureWrap::Clamp;
      else if (t.source != TextureSource::Checkerboard)
        fail(v, "unknown Appearance '" + a + "' (expected " +
                    (t.source == TextureSource::Perlin ? "patch or vein" : "repeat or clamp") + ")");
    }
    t.bump = bool_attr(c, "bumpmap", false);
    if (const auto m = attr(c, "bumpmapMultiplier")) t.bump_factor = parse_float(*m, attr_source(c, "bumpmapMultiplier"));
    add_texture(c, std::move(t));
  }

  // 2021: <TextureMap id type="image|perlin|checkerboard"> with ImageId into <Images>.
  void read_texture_map_2021(Node c) {
    warn_unknown_children(c, {"ImageId", "Interpolation", "DecalMode", "Normalizer", "BumpFactor", "NoiseConversion",
                              "NoiseScale", "Scale", "Offset", "BlackColor", "WhiteColor", "Appearance"});
    TextureDesc t;
    const auto type = attr(c, "type");
    if (!type) fail(c, "missing type attribute");
    if (*type == "image") {
      t.source = TextureSource::Image;
      Node img = req_child(c, "ImageId");
      const int id = get_int(img);
      const auto it = image_paths_.find(id);
      if (it == image_paths_.end()) fail(img, "Image " + std::to_string(id) + " is not defined");
      t.image_path = uses_file(it->second);
    } else if (*type == "perlin") {
      t.source = TextureSource::Perlin;
    } else if (*type == "checkerboard") {
      t.source = TextureSource::Checkerboard;
    } else {
      fail(c, "unknown TextureMap type '" + *type + "' (expected image, perlin or checkerboard)");
    }
    read_common_texture_children(c, t);
    if (Node v = opt_child(c, "NoiseConversion")) {
      static constexpr std::pair<std::string_view, NoiseConversion> kConv[] = {{"linear", NoiseConversion::Linear},
                                                                               {"absval", NoiseConversion::AbsVal}};
      t.noise = keyword(v, kConv, "NoiseConversion");
    }
    if (Node v = opt_child(c, "Appearance")) {
      static constexpr std::pair<std::string_view, TextureWrap> kWraps[] = {{"repeat", TextureWrap::Repeat},
                                                                           {"clamp", TextureWrap::Clamp}};
      t.wrap = keyword(v, kWraps, "Appearance");
    }
    add_texture(c, std::move(t));
  }

  std::vector<int> read_texture_refs(Node obj) {
    std::vector<int> out;
    for (const char* name : {"Texture", "Textures"}) {
      Node n = opt_child(obj, name);
      if (!n) continue;
      for (int64_t id : parse_ints(text_of(n), source(n))) {
        const auto it = texture_index_.find(int(id));
        if (it == texture_index_.end()) fail(n, "texture " + std::to_string(id) + " is not defined");
        out.push_back(it->second);
      }
    }
    return out;
  }

  // ---- cameras -----------------------------------------------------------------------------------------------
  void read_camera(Node c) {
    warn_unknown_children(c, kCameraChildren);
    CameraDesc cam;
    cam.id = attr(c, "id").value_or(std::to_string(scene_.cameras.size() + 1));
    const auto type = attr(c, "type");
    const bool fov_type = type && (*type == "lookAt" || *type == "simple");
    if (type && !fov_type) fail(c, "unknown camera type '" + *type + "' (expected lookAt or simple)");
    if (const auto h = attr(c, "handedness")) {
      if (*h != "left" && *h != "right") fail(c, "handedness must be left or right, got '" + *h + "'");
      cam.left_handed = *h == "left";
    }
    cam.position = get_vec3(req_child(c, "Position"));
    Node gaze = opt_child(c, "Gaze"), gaze_point = opt_child(c, "GazePoint");
    if (gaze && gaze_point) fail(c, "has both <Gaze> and <GazePoint>");
    if (!gaze && !gaze_point) fail(c, "missing <Gaze> (or <GazePoint>)");
    cam.gaze = gaze ? get_vec3(gaze) : get_vec3(gaze_point) - cam.position;
    if (!is_finite(cam.gaze)) fail(gaze_point, "GazePoint - Position overflows single precision");
    if (length_squared(cam.gaze) == 0.0f) fail(gaze ? gaze : gaze_point, "gaze direction is zero");
    Node up = req_child(c, "Up");
    cam.up = get_vec3(up);
    if (length_squared(cross(cam.gaze, cam.up)) == 0.0f) fail(up, "Up is zero or parallel to the gaze direction");

    Node near_plane = opt_child(c, "NearPlane"), fov = opt_child(c, "FovY");
    if (!near_plane && !fov) fail(c, "missing <NearPlane> (or <FovY>)");
    cam.use_fov = fov && (fov_type || !near_plane);
    if (cam.use_fov) {
      cam.fov_y_deg = get_float(fov);
      if (!(cam.fov_y_deg > 0.0f && cam.fov_y_deg < kMaxFovYDeg))
        fail(fov, "FovY must be in (0, 180) degrees, got " + std::to_string(cam.fov_y_deg));
    } else {
      const auto v = parse_floats(text_of(near_plane), source(near_plane));
      if (v.size() < 4) fail(near_plane, "expected 4 numbers (left right bottom top), got " + std::to_string(v.size()));
      if (v.size() > 4)
        warn(near_plane, "NearPlane has " + std::to_string(v.size()) + " numbers; using the first four");
      std::copy(v.begin(), v.begin() + 4, cam.near_plane.begin());
      if (!(cam.near_plane[0] < cam.near_plane[1]) || !(cam.near_plane[2] < cam.near_plane[3]))
        fail(near_plane, "NearPlane must have left < right and bottom < top");
    }
    if (Node d = cam.use_fov ? opt_child(c, "NearDistance") : req_child(c, "NearDistance"))
      cam.near_distance = positive(d, get_float(d), "NearDistance");

    Node res = req_child(c, "ImageResolution");
    const auto wh = parse_ints(text_of(res), source(res));
    if (wh.size() != 2) fail(res, "expected 2 integers (width height), got " + std::to_string(wh.size()));
    if (wh[0] <= 0 || wh[1] <= 0 || wh[0] > std::numeric_limits<int>::max() || wh[1] > std::numeric_limits<int>::max())
      fail(res, "image resolution must be positive");
    cam.width = int(wh[0]);
    cam.height = int(wh[1]);

    Node name = req_child(c, "ImageName");
    const std::string image = get_string(name);
    cam.image_name = fs::path(image).filename().string();
    if (cam.image_name.empty() || cam.image_name == "." || cam.image_name == "..")
      fail(name, "ImageName '" + image + "' is not a file name");
    if (cam.image_name != image) warn(name, "ImageName '" + image + "': directory part ignored");

    if (Node s = opt_child(c, "NumSamples")) {
      cam.num_samples = get_int(s);
      if (cam.num_samples < 1) fail(s, "NumSamples must be at least 1");
    }
    if (Node a = opt_child(c, "ApertureSize")) cam.aperture_size = non_negative(a, get_float(a), "ApertureSize");
    if (Node f = opt_child(c, "FocusDistance")) cam.focus_distance = positive(f, get_float(f), "FocusDistance");
    if (cam.aperture_size > 0.0f && cam.focus_distance == 0.0f) fail(c, "ApertureSize needs a <FocusDistance>");

    if (Node t = opt_child(c, "Tonemap")) cam.tonemap = read_tonemap(t);
    if (Node g = opt_child(c, "GammaCorrection")) {  // 2018
      const std::string v = get_string(g);
      if (!cam.tonemap) {
        if (is_srgb(v))
          cam.srgb_without_tonemap = true;
        else
          warn(g, "GammaCorrection " + v + " without a Tonemap is ignored (only sRGB applies to the LDR preview)");
      } else if (is_srgb(v)) {
        cam.tonemap->srgb = true;
      } else {
        cam.tonemap->gamma = positive(g, parse_float(v, source(g)), "GammaCorrection");
      }
    }
    if (Node r = opt_child(c, "Renderer")) {
      cam.renderer = read_renderer(r);
      cam.renderer_explicit = true;
    }
    if (Node p = opt_child(c, "RendererParams")) cam.pt = read_renderer_params(p);
    scene_.cameras.push_back(std::move(cam));
  }

  static bool is_srgb(std::string_view v) {
    return v.size() == 4 && (v[0] == 's' || v[0] == 'S') && (v.substr(1) == "RGB" || v.substr(1) == "rgb");
  }

  TonemapDesc read_tonemap(Node t) {
    warn_unknown_children(t, {"TMO", "TMOOptions", "Saturation", "Gamma"});
    TonemapDesc tm;
    if (Node n = opt_child(t, "TMO")) tm.tmo = get_string(n);
    if (Node n = opt_child(t, "TMOOptions")) {
      const auto v = parse_floats(text_of(n), source(n));
      if (v.empty() || v.size() > 2) fail(n, "expected 2 numbers (key burn_percent), got " + std::to_string(v.size()));
      tm.key = positive(n, v[0], "key");
      if (v.size() > 1) {
        tm.burn_percent = v[1];
        if (v[1] < 0.0f || v[1] > kMaxBurnPercent) fail(n, "burn percentage must be in [0, 100]");
      }
    }
    if (Node n = opt_child(t, "Saturation")) tm.saturation = non_negative(n, get_float(n), "Saturation");
    if (Node n = opt_child(t, "Gamma")) {
      const std::string v = get_string(n);
      if (is_srgb(v))
        tm.srgb = true;
      else
        tm.gamma = positive(n, parse_float(v, source(n)), "Gamma");
    }
    return tm;
  }

  // Kiln's extension <Scene rules="kiln">: a scene written for Kiln in this format renders with Kiln's rules; any
  // other CENG795 file is a course scene (README, "Two rule sets").
  SceneRules read_rules(Node scene) const {
    const auto v = attr(scene, "rules");
    if (!v || *v == "course") return SceneRules::Ceng795Course;
    if (*v == "kiln") return SceneRules::Kiln;
    fail(scene, "unknown rules '" + *v + "' (kiln, course)");
  }

  RendererKind read_renderer(Node r) const {
    const std::string v = get_string(r);
    if (v == "PathTracing") return RendererKind::PathTracing;
    fail(r, "unsupported renderer '" + v + "' (only PathTracing)");
  }
  PathTracingFlags read_renderer_params(Node p) {
    warn_unknown_children(p, {});
    PathTracingFlags f;
    const std::string text = text_of(p);
    for (std::string_view tok : split_whitespace(text)) {
      if (tok == "NextEventEstimation")
        f.next_event_estimation = true;
      else if (tok == "ImportanceSampling")
        f.importance_sampling = true;
      else if (tok == "RussianRoulette")
        f.russian_roulette = true;
      else
        fail(p, "unknown renderer parameter '" + std::string(tok) +
                    "' (expected NextEventEstimation, ImportanceSampling, RussianRoulette)");
    }
    return f;
  }
  // 2018: <Integrator>/<IntegratorParams> at Scene level apply to every camera that names no renderer itself.
  void read_scene_integrator() {
    Node integ = opt_child(root_, "Integrator"), params = opt_child(root_, "IntegratorParams");
    if (!integ && !params) return;
    if (!integ) fail(params, "IntegratorParams without an <Integrator>");
    const RendererKind kind = read_renderer(integ);
    const PathTracingFlags flags = params ? read_renderer_params(params) : PathTracingFlags{};
    for (auto& cam : scene_.cameras) {
      if (cam.renderer_explicit) continue;
      cam.renderer = kind;
      cam.renderer_explicit = true;
      cam.pt = flags;
    }
  }

  // ---- lights ------------------------------------------------------------------------------------------------
  void read_lights(Node n) {
    warn_unknown_children(
        n, {"AmbientLight", "PointLight", "DirectionalLight", "SpotLight", "AreaLight", "SphericalDirectionalLight"});
    if (Node a = opt_child(n, "AmbientLight")) scene_.ambient_light = get_rgb(a);
    for (Node l : n.children("PointLight")) {
      warn_unknown_children(l, {"Position", "Intensity"});
      scene_.point_lights.push_back({get_vec3(req_child(l, "Position")), get_rgb(req_child(l, "Intensity"))});
    }
    for (Node l : n.children("DirectionalLight")) {
      warn_unknown_children(l, {"Direction", "Radiance"});
      Node d = req_child(l, "Direction");
      scene_.directional_lights.push_back({nonzero(d, get_vec3(d)), get_rgb(req_child(l, "Radiance"))});
    }
    for (Node l : n.children("SpotLight")) {
      warn_unknown_children(l, {"Position", "Direction", "Intensity", "CoverageAngle", "FalloffAngle"});
      SpotLightDesc s;
      s.position = get_vec3(req_child(l, "Position"));
      Node d = req_child(l, "Direction");
      s.direction = nonzero(d, get_vec3(d));
      s.intensity = get_rgb(req_child(l, "Intensity"));
      s.coverage_deg = cone_angle(req_child(l, "CoverageAngle"));
      s.falloff_deg = cone_angle(req_child(l, "FalloffAngle"));
      if (s.falloff_deg > s.coverage_deg) fail(l, "FalloffAngle must not exceed CoverageAngle");
      scene_.spot_lights.push_back(s);
    }
    for (Node l : n.children("AreaLight")) read_area_light(l);
    for (Node l : n.children("SphericalDirectionalLight")) {
      warn_unknown_children(l, {"EnvMapName", "ImageId"});
      Node name = opt_child(l, "EnvMapName"), image = opt_child(l, "ImageId");
      if (!name && !image) fail(l, "missing <EnvMapName> (or <ImageId>)");
      EnvLightDesc e;
      Node named = name ? name : image;
      if (name) {
        e.image_path = resolve(get_string(name));
      } else {
        const int id = get_int(image);
        const auto it = image_paths_.find(id);
        if (it == image_paths_.end()) fail(image, "Image " + std::to_string(id) + " is not defined");
        e.image_path = it->second;
      }
      // Checked here, where the element is known; the renderer reads (and names) it when it builds the light.
      std::error_code ec;
      if (!fs::is_regular_file(e.image_path, ec)) fail(named, "environment map '" + e.image_path + "' does not exist");
      uses_file(e.image_path);
      e.element = location(l);
      scene_.env_lights.push_back(e);
    }
  }

  void read_area_light(Node l) {
    warn_unknown_children(l, {"Position", "Normal", "Size", "EdgeVector1", "EdgeVector2", "Radiance", "Intensity"});
    AreaLightDesc a;
    a.position = get_vec3(req_child(l, "Position"));
    Node normal = opt_child(l, "Normal"), e1 = opt_child(l, "EdgeVector1");
    if (normal && e1) fail(l, "has both <Normal> and <EdgeVector1>");
    if (normal) {
      a.normal = unit(normal, get_vec3(normal));
      Node size = req_child(l, "Size");
      a.size = positive(size, get_float(size), "Size");
    } else if (e1) {
      const Vec3f u = get_vec3(e1), v = get_vec3(req_child(l, "EdgeVector2"));
      const Vec3f n = cross(u, v);
      if (length_squared(n) == 0.0f) fail(l, "EdgeVector1 and EdgeVector2 are parallel or zero");
      if (!is_finite(n)) fail(l, "EdgeVector1 x EdgeVector2 overflows single precision");
      a.edges = std::array<Vec3f, 2>{u, v};
      a.normal = unit(l, n);
    } else {
      fail(l, "missing <Normal> and <Size> (or <EdgeVector1> and <EdgeVector2>)");
    }
    Node rad = opt_child(l, "Radiance"), inten = opt_child(l, "Intensity");
    if (rad && inten) fail(l, "has both <Radiance> and <Intensity>");
    if (!rad && !inten) fail(l, "missing <Radiance> (or <Intensity>)");
    a.radiance = get_rgb(rad ? rad : inten);
    a.radiance_is_intensity = !rad;
    scene_.area_lights.push_back(a);
  }

  Vec3f nonzero(Node n, Vec3f v) const {
    if (length_squared(v) == 0.0f) fail(n, "vector must not be zero");
    return v;
  }
  // Unit vector along a non-zero v, scaled by its largest component first so that |v|^2 neither overflows
  // (a 1e30 vector would normalise to zero) nor underflows.
  Vec3f unit(Node n, Vec3f v) const {
    const float largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (largest == 0.0f) fail(n, "vector must not be zero");
    return normalize(v / largest);
  }
  float cone_angle(Node n) const {
    const float a = get_float(n);
    if (!(a > 0.0f && a <= kMaxConeAngleDeg)) fail(n, "angle must be in (0, 180] degrees");
    return a;
  }

  // ---- objects -----------------------------------------------------------------------------------------------
  void read_objects(Node n) {
    warn_unknown_children(n, {"Mesh", "MeshInstance", "Triangle", "Sphere", "LightMesh", "LightSphere"});
    for (Node c : n.children()) {
      if (c.type() != pugi::node_element) continue;
      const std::string_view kind = c.name();
      if (kind == "Mesh" || kind == "LightMesh")
        read_mesh(c, kind == "LightMesh");
      else if (kind == "Triangle")
        read_triangle(c);
      else if (kind == "Sphere" || kind == "LightSphere")
        read_sphere(c, kind == "LightSphere");
    }
  }

  // Ids are per element kind (a Mesh id=1 and a Sphere id=1 coexist). Only Mesh ids are ever referenced (by
  // baseMeshId), so a repeated id (hw1_2021 two_spheres.xml has two Sphere id=1) is a warning; an instance that
  // names a repeated Mesh id is an error.
  int object_id(Node c) {
    const int id = id_of(c);
    if (!object_ids_[c.name()].insert(id).second) {
      warn(c, "duplicate " + std::string(c.name()) + " id " + std::to_string(id));
      if (std::string_view(c.name()) == "Mesh") ambiguous_mesh_ids_.insert(id);
    }
    return id;
  }
  int material_ref(Node obj, bool required) const {
    Node n = required ? req_child(obj, "Material") : opt_child(obj, "Material");
    if (!n) return -1;
    const int id = get_int(n);
    const auto it = material_index_.find(id);
    if (it == material_index_.end()) fail(n, "Material " + std::to_string(id) + " is not defined");
    return it->second;
  }
  // The object's translation over the shutter interval, in world space (format doc: translated by t * (x y z)).
  Vec3f read_motion_blur(Node obj) const {
    Node m = opt_child(obj, "MotionBlur");
    return m ? get_vec3(m) : Vec3f(0.0f);
  }
  std::optional<bool> shading_mode(Node obj) const {
    const auto s = attr(obj, "shadingMode");
    if (!s) return std::nullopt;
    if (*s == "smooth") return true;
    if (*s == "flat") return false;
    fail(obj, "shadingMode must be flat or smooth, got '" + *s + "'");
  }

  void read_mesh(Node c, bool light) {
    warn_unknown_children(c, light ? std::initializer_list<std::string_view>{"Material", "Radiance", "Faces",
                                                                             "Transformations", "MotionBlur"}
                                   : std::initializer_list<std::string_view>{"Material", "Faces", "Transformations",
                                                                             "MotionBlur", "Texture", "Textures"});
    MeshDesc m;
    const int id = object_id(c);
    m.name = std::string(c.name()) + " id=" + std::to_string(id);
    m.material = material_ref(c, !light);
    m.to_world = object_transform(c);
    m.smooth = shading_mode(c).value_or(false);
    // Kiln extension: <Mesh subdivide="N"> Loop-subdivides the mesh N times after loading.
    m.subdivide = int_attr(c, "subdivide", 0);
    if (m.subdivide < 0 || m.subdivide > kMaxSubdivisionLevels)
      fail(c, "subdivide must be 0.." + std::to_string(kMaxSubdivisionLevels) + ", got " + std::to_string(m.subdivide));
    if (light) m.emission = get_rgb(req_child(c, "Radiance"));
    read_faces(req_child(c, "Faces"), m);
    m.motion = read_motion_blur(c);
    m.textures = read_texture_refs(c);
    if (!light) mesh_index_.emplace(id, int(scene_.meshes.size()));  // the first of repeated ids
    scene_.meshes.push_back(std::move(m));
  }

  void read_triangle(Node c) {
    warn_unknown_children(c, {"Material", "Indices", "Transformations", "MotionBlur", "Texture", "Textures"});
    MeshDesc m;
    m.name = "Triangle id=" + std::to_string(object_id(c));
    m.material = material_ref(c, true);
    m.to_world = object_transform(c);
    Node ind = req_child(c, "Indices");
    const auto idx = parse_ints(text_of(ind), source(ind));
    if (idx.size() != 3) fail(ind, "expected 3 vertex indices, got " + std::to_string(idx.size()));
    build_indexed(ind, idx, 0, 0, false, m);
    m.motion = read_motion_blur(c);
    m.textures = read_texture_refs(c);
    scene_.meshes.push_back(std::move(m));
  }

  void read_sphere(Node c, bool light) {
    warn_unknown_children(
        c, light ? std::initializer_list<std::string_view>{"Material", "Center", "Radius", "Radiance",
                                                           "Transformations", "MotionBlur"}
                 : std::initializer_list<std::string_view>{"Material", "Center", "Radius", "Transformations",
                                                           "MotionBlur", "Texture", "Textures"});
    SphereDesc s;
    s.name = std::string(c.name()) + " id=" + std::to_string(object_id(c));
    s.material = material_ref(c, !light);
    s.to_world = object_transform(c);
    Node center = req_child(c, "Center");
    s.center = vertex(center, get_int(center), 0);
    Node radius = req_child(c, "Radius");
    s.radius = positive(radius, get_float(radius), "Radius");
    if (light) s.emission = get_rgb(req_child(c, "Radiance"));
    s.motion = read_motion_blur(c);
    s.textures = read_texture_refs(c);
    scene_.spheres.push_back(s);
  }

  void read_instance(Node c) {
    warn_unknown_children(c, {"Material", "Transformations", "MotionBlur", "Texture", "Textures"});
    InstanceDesc inst;
    inst.name = "MeshInstance id=" + std::to_string(object_id(c));
    if (!c.attribute("baseMeshId")) fail(c, "missing baseMeshId attribute");
    const int base_id = int_attr(c, "baseMeshId", 0);
    const auto it = mesh_index_.find(base_id);
    if (it == mesh_index_.end()) fail(c, "baseMeshId " + std::to_string(base_id) + " is not a defined Mesh id");
    if (ambiguous_mesh_ids_.count(base_id))
      fail(c, "baseMeshId " + std::to_string(base_id) + " is ambiguous: several Mesh elements have that id");
    inst.base_mesh = it->second;
    MeshDesc& base = scene_.meshes[size_t(inst.base_mesh)];
    base.is_instance_base = true;
    const Transform own = object_transform(c);
    inst.to_world = bool_attr(c, "resetTransform", false) ? own : own * base.to_world;
    if (!transform_is_finite(inst.to_world)) fail(c, "the composed transformation overflows single precision");
    inst.material = material_ref(c, false);
    if (inst.material < 0) inst.material = base.material;
    inst.smooth = shading_mode(c);
    inst.motion = read_motion_blur(c);
    inst.textures = read_texture_refs(c);
    if (inst.textures.empty()) inst.textures = base.textures;
    scene_.instances.push_back(inst);
  }

  // Vertex `listed` as written in the file (1-based unless ZeroBasedIndexing) plus `offset`.
  Vec3f vertex(Node n, int64_t listed, int64_t offset) const {
    const int64_t g = listed - index_base() + offset;
    if (g < 0 || uint64_t(g) >= vertices_.size()) fail(n, out_of_range(listed, offset));
    return vertices_[size_t(g)];
  }
  int64_t index_base() const { return zero_based_ ? 0 : 1; }
  std::string out_of_range(int64_t listed, int64_t offset) const {
    return "vertex index " + std::to_string(listed) +
           (offset ? " (+ vertexOffset " + std::to_string(offset) + ")" : "") + " is out of range: VertexData has " +
           std::to_string(vertices_.size()) + " vertices (" + (zero_based_ ? "0-based" : "1-based") + " indices)";
  }

  void read_faces(Node faces, MeshDesc& m) {
    if (const auto ply = attr(faces, "plyFile")) {
      if (faces.attribute("vertexOffset") || faces.attribute("textureOffset"))
        warn(faces, "vertexOffset/textureOffset are ignored with plyFile");
      MeshDesc p;
      try {
        p = load_ply(resolve(*ply));
      } catch (const Error& e) {
        fail(faces, "plyFile '" + *ply + "': " + e.what());
      }
      m.positions = std::move(p.positions);
      m.indices = std::move(p.indices);
      m.normals = std::move(p.normals);
      m.uvs = std::move(p.uvs);
    } else {
      const int64_t vo = int_attr(faces, "vertexOffset", 0), to = int_attr(faces, "textureOffset", 0);
      std::vector<int64_t> idx;
      if (const auto bin = attr(faces, "binaryFile"))
        idx = read_binary_faces(faces, *bin);
      else
        idx = parse_ints(text_of(faces), source(faces));
      if (idx.size() % 3 != 0) fail(faces, "has " + std::to_string(idx.size()) + " indices, not a multiple of 3");
      build_indexed(faces, idx, vo, to, faces.attribute("textureOffset"), m);
    }
    if (m.indices.empty()) warn(faces, "mesh has no triangles");
  }

  // binaryFile layout (course 2019): little-endian int32 triangle count N, then N x 3 int32 indices.
  std::vector<int64_t> read_binary_faces(Node n, const std::string& rel) {
    const std::string bytes = read_referenced(n, "binaryFile", rel);
    if (bytes.size() < 4) fail(n, "binaryFile '" + rel + "' is truncated (no count)");
    const int32_t count = int32_t(le_u32(bytes.data()));
    if (count < 0) fail(n, "binaryFile '" + rel + "' has a negative count " + std::to_string(count));
    const uint64_t need = 4 + uint64_t(count) * 12;
    if (bytes.size() < need)
      fail(n, "binaryFile '" + rel + "' is truncated: " + std::to_string(count) + " triangles need " +
                  std::to_string(need) + " bytes, file has " + std::to_string(bytes.size()));
    if (bytes.size() > need) warn(n, "binaryFile '" + rel + "' has trailing bytes after its data");
    std::vector<int64_t> out(size_t(count) * 3);
    for (size_t i = 0; i < out.size(); ++i) out[i] = int32_t(le_u32(bytes.data() + 4 + 4 * i));
    return out;
  }

  // Builds a compact mesh from global vertex indices as written in the file.
  void build_indexed(Node n, const std::vector<int64_t>& listed, int64_t vertex_offset, int64_t texture_offset,
                     bool explicit_texture_offset, MeshDesc& m) {
    remap_.resize(vertices_.size(), kUnmapped);
    std::vector<uint32_t> globals;  // local -> global vertex
    m.indices.reserve(listed.size());
    for (size_t k = 0; k < listed.size(); ++k) {
      // An index this large is out of range anyway; checking first keeps "- base + offset" from overflowing.
      const bool representable = listed[k] >= -kMaxListedIndex && listed[k] <= kMaxListedIndex;
      const int64_t g = representable ? listed[k] - index_base() + vertex_offset : -1;
      if (g < 0 || uint64_t(g) >= vertices_.size()) {
        for (uint32_t gv : globals) remap_[gv] = kUnmapped;
        fail(n, "triangle " + std::to_string(k / 3 + 1) + ": " + out_of_range(listed[k], vertex_offset));
      }
      uint32_t& local = remap_[size_t(g)];
      if (local == kUnmapped) {
        local = uint32_t(globals.size());
        globals.push_back(uint32_t(g));
      }
      m.indices.push_back(local);
    }
    for (uint32_t gv : globals) remap_[gv] = kUnmapped;

    m.positions.resize(globals.size());
    for (size_t i = 0; i < globals.size(); ++i) m.positions[i] = vertices_[globals[i]];
    if (texcoords_.empty()) return;
    // uv index of a vertex = listed - base + textureOffset = global - vertexOffset + textureOffset.
    const int64_t shift = texture_offset - vertex_offset;
    bool all = true;
    for (uint32_t g : globals) {
      const int64_t t = int64_t(g) + shift;
      if (t < 0 || uint64_t(t) >= texcoords_.size()) {
        if (explicit_texture_offset)
          fail(n, "texture coordinate index " + std::to_string(t + index_base() - texture_offset) +
                      " (+ textureOffset " + std::to_string(texture_offset) + ") is out of range: TexCoordData has " +
                      std::to_string(texcoords_.size()) + " entries");
        all = false;
        break;
      }
    }
    if (!all) return;
    m.uvs.resize(globals.size());
    for (size_t i = 0; i < globals.size(); ++i) m.uvs[i] = texcoords_[size_t(int64_t(globals[i]) + shift)];
  }

  std::string file_;
  fs::path dir_;
  std::string text_;
  std::vector<size_t> line_starts_;
  Node root_;
  SceneDesc scene_;

  bool zero_based_ = false;
  std::vector<Vec3f> vertices_;
  std::vector<Vec2f> texcoords_;
  std::vector<uint32_t> remap_;  // global -> local vertex while building one mesh; kUnmapped otherwise
  std::unordered_map<int, Transform> xforms_[kXformKinds];
  std::unordered_map<int, int> brdf_index_, material_index_, mesh_index_;
  std::unordered_map<std::string, std::unordered_set<int>> object_ids_;
  std::unordered_set<int> ambiguous_mesh_ids_;
  std::unordered_map<int, int> texture_index_;  // XML id -> index into SceneDesc::textures
  std::unordered_map<int, std::string> image_paths_;
};

}  // namespace

SceneDesc load_ceng795_xml(const std::string& path) { return XmlLoader(path).load(); }

}  // namespace kiln
