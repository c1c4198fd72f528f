// pbrt-v4 Texture directives into SceneDesc::pbrt_textures (scenes/texture_graph.h), and the texture references of
// material parameters. Every class of pbrt-v4's file-format documentation is read except ptex (warned: Kiln has no
// Ptex reader; parameters that use one keep their defaults). An unknown class, a missing image, a reference to a
// texture that does not exist or is of the other kind (float / spectrum) is an error naming the file and line.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "scenes/pbrt/builder.h"

namespace kiln {
namespace {

struct ClassInfo {
  const char* name;
  TextureClass cls;
  bool has_float, has_spectrum;
};
constexpr std::array<ClassInfo, 12> kClasses = {{
    {"constant", TextureClass::Constant, true, true},
    {"scale", TextureClass::Scale, true, true},
    {"mix", TextureClass::Mix, true, true},
    {"directionmix", TextureClass::DirectionMix, true, true},
    {"checkerboard", TextureClass::Checkerboard, true, true},
    {"dots", TextureClass::Dots, true, true},
    {"bilerp", TextureClass::Bilerp, true, true},
    {"imagemap", TextureClass::ImageMap, true, true},
    {"fbm", TextureClass::Fbm, true, false},
    {"wrinkled", TextureClass::Wrinkled, true, false},
    {"windy", TextureClass::Windy, true, false},
    {"marble", TextureClass::Marble, false, true},
}};

std::string class_list() {
  std::string s;
  for (const ClassInfo& c : kClasses) s += std::string(s.empty() ? "" : ", ") + c.name;
  return s + ", ptex";
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                    [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

ImageFilter parse_filter(const PbrtParams& ps, const std::string& f) {
  if (f == "point") return ImageFilter::Point;
  if (f == "bilinear") return ImageFilter::Bilinear;
  if (f == "trilinear") return ImageFilter::Trilinear;
  if (f == "ewa" || f == "EWA") return ImageFilter::Ewa;
  ps.fail(ps.line(), "unknown \"filter\" " + in_quotes(f) + " (point, bilinear, trilinear, ewa)");
}

ImageWrap parse_wrap(const PbrtParams& ps, const std::string& w) {
  if (w == "repeat") return ImageWrap::Repeat;
  if (w == "black") return ImageWrap::Black;
  if (w == "clamp") return ImageWrap::Clamp;
  if (w == "octahedralsphere") return ImageWrap::OctahedralSphere;
  ps.fail(ps.line(), "unknown \"wrap\" " + in_quotes(w) + " (repeat, black, clamp, octahedralsphere)");
}

// pbrt-v4's ColorEncoding names: "linear", "sRGB", "gamma G".
void parse_encoding(const PbrtParams& ps, const std::string& e, ImageTextureDesc& image) {
  if (e == "linear") {
    image.encoding = ImageEncoding::Linear;
  } else if (e == "sRGB") {
    image.encoding = ImageEncoding::Srgb;
  } else if (e.rfind("gamma ", 0) == 0) {
    image.encoding = ImageEncoding::Gamma;
    char* end = nullptr;
    const std::string g = e.substr(6);
    image.gamma = std::strtof(g.c_str(), &end);
    if (end == g.c_str() || *end != '\0' || !(image.gamma > 0.0f) || !std::isfinite(image.gamma))
      ps.fail(ps.line(), "\"encoding\" " + in_quotes(e) + ": the gamma must be a positive number");
  } else {
    ps.fail(ps.line(), "unknown \"encoding\" " + in_quotes(e) + " (linear, sRGB, \"gamma 2.2\")");
  }
}

}  // namespace

int PbrtBuilder::texture_ref(const PbrtParams& ps, const std::string& param, const std::string& tex, bool is_float) {
  const auto it = textures_.find({tex, is_float});
  if (it == textures_.end()) {
    const char* kind = is_float ? "float" : "spectrum";
    if (textures_.count({tex, !is_float}))
      ps.fail(ps.line(), in_quotes(param) + " needs a " + kind + " texture, but " + in_quotes(tex) + " is a " +
                             (is_float ? "spectrum" : "float") + " texture");
    ps.fail(ps.line(), in_quotes(param) + ": no " + kind + " texture named " + in_quotes(tex) +
                           " (Texture defines them)");
  }
  if (it->second.index < 0) {
    diag_.warn(ps, in_quotes(param) + " uses texture " + in_quotes(tex) + " (" + in_quotes(it->second.cls) +
                       "), which Kiln does not render; the default is used");
  }
  return it->second.index;
}

// A constant texture is read as its value (no texture at the hit); others are referenced.
TexturedFloat PbrtBuilder::float_param(const PbrtParams& ps, const std::string& name, float def) {
  if (const auto tex = ps.find_texture(name)) {
    const int i = texture_ref(ps, name, *tex, true);
    if (i < 0) return {def, -1};
    const PbrtTextureDesc& t = scene_.pbrt_textures[size_t(i)];
    if (t.cls == TextureClass::Constant && !t.operands[0].textured()) return {t.operands[0].value.r, -1};
    return {def, i};
  }
  return {ps.get_float(name, def), -1};
}

TexturedRgb PbrtBuilder::spectrum_param(const PbrtParams& ps, const std::string& name, SpectrumUse use, Rgb def) {
  if (const auto tex = ps.find_texture(name)) {
    const int i = texture_ref(ps, name, *tex, false);
    if (i < 0) return {def, -1};
    const PbrtTextureDesc& t = scene_.pbrt_textures[size_t(i)];
    if (t.cls == TextureClass::Constant && !t.operands[0].textured()) {
      Rgb c = t.operands[0].value;
      if (use == SpectrumUse::Albedo && c.max_component() > 1.0f) {
        diag_.warn(ps, "texture " + in_quotes(*tex) + " used as " + in_quotes(name) + " exceeds 1; clamped");
        c = Rgb(std::min(c.r, 1.0f), std::min(c.g, 1.0f), std::min(c.b, 1.0f));
      }
      return {c, -1};
    }
    return {def, i};
  }
  return {ps.find_spectrum(name, use).value_or(def), -1};
}

void PbrtBuilder::read_mapping(const PbrtParams& ps, const Transform& to_world, TextureMappingDesc& m) {
  const std::string kind = ps.get_string("mapping", "uv");
  m.world_to_texture = to_world.inverse();
  if (kind == "uv") {
    m.kind = TextureMapping::Uv;
    m.su = ps.get_float("uscale", 1.0f);
    m.sv = ps.get_float("vscale", 1.0f);
  } else if (kind == "spherical") {
    m.kind = TextureMapping::Spherical;
  } else if (kind == "cylindrical") {
    m.kind = TextureMapping::Cylindrical;
  } else if (kind == "planar") {
    m.kind = TextureMapping::Planar;
    m.v1 = ps.find_vector3("v1").value_or(Vec3f(1, 0, 0));
    m.v2 = ps.find_vector3("v2").value_or(Vec3f(0, 1, 0));
  } else {
    ps.fail(ps.line(), "unknown \"mapping\" " + in_quotes(kind) + " (uv, spherical, cylindrical, planar)");
  }
  if (kind == "uv" || kind == "planar") {
    m.du = ps.get_float("udelta", 0.0f);
    m.dv = ps.get_float("vdelta", 0.0f);
  }
}

void PbrtBuilder::read_image_texture(const PbrtParams& ps, ImageTextureDesc& image) {
  const auto file = ps.find_string("filename");
  if (!file) ps.fail(ps.line(), "an imagemap needs \"string filename\"");
  image.path = resolve_(*file, ps);
  image.filter = parse_filter(ps, ps.get_string("filter", "bilinear"));
  image.wrap = parse_wrap(ps, ps.get_string("wrap", "repeat"));
  // pbrt-v4's default: 8-bit PNGs are sRGB, everything else linear.
  parse_encoding(ps, ps.get_string("encoding", ends_with(image.path, ".png") ? "sRGB" : "linear"), image);
  image.scale = ps.get_float("scale", 1.0f);
  image.invert = ps.get_bool("invert", false);
  ps.get_float("maxanisotropy", 8.0f);  // OpenImageIO bounds the anisotropy itself
  if (!std::isfinite(image.scale)) ps.fail(ps.line(), "\"scale\" must be finite");
  add_external_file(image.path);
}

void PbrtBuilder::add_external_file(const std::string& path) {
  std::vector<std::string>& files = scene_.external_files;
  if (std::find(files.begin(), files.end(), path) == files.end()) files.push_back(path);
}

int PbrtBuilder::add_image_texture(const std::string& name, const ImageTextureDesc& image, bool is_float) {
  PbrtTextureDesc t;
  t.name = name;
  t.cls = TextureClass::ImageMap;
  t.is_float = is_float;
  t.image = image;
  scene_.pbrt_textures.push_back(std::move(t));
  add_external_file(image.path);
  return int(scene_.pbrt_textures.size()) - 1;
}

// Operands as pbrt-v4 reads them (with its defaults); float operands of spectrum textures are float textures.
void PbrtBuilder::read_operands(const PbrtParams& ps, PbrtTextureDesc& t) {
  const auto value = [&](const char* name, float def) -> TexturedRgb {
    if (t.is_float) {
      const TexturedFloat f = float_param(ps, name, def);
      return {Rgb(f.value), f.texture};
    }
    return spectrum_param(ps, name, SpectrumUse::Unbounded, Rgb(def));
  };
  const auto amount = [&](const char* name, float def) -> TexturedRgb {
    const TexturedFloat f = float_param(ps, name, def);
    return {Rgb(f.value), f.texture};
  };
  const auto constant = [&](const char* name, float def) -> TexturedRgb {
    if (t.is_float) return {Rgb(ps.get_float(name, def)), -1};
    return {ps.find_spectrum(name, SpectrumUse::Unbounded).value_or(Rgb(def)), -1};
  };
  auto& in = t.operands;
  switch (t.cls) {
    case TextureClass::Constant: in[0] = constant("value", 1.0f); break;
    case TextureClass::Scale:
      in[kTexOperandTex] = value("tex", 1.0f);
      in[kTexOperandScale] = amount("scale", 1.0f);
      break;
    case TextureClass::Mix:
      in[kTexOperandTex1] = value("tex1", 0.0f);
      in[kTexOperandTex2] = value("tex2", 1.0f);
      in[kTexOperandAmount] = amount("amount", 0.5f);
      break;
    case TextureClass::DirectionMix:
      in[kTexOperandTex1] = value("tex1", 0.0f);
      in[kTexOperandTex2] = value("tex2", 1.0f);
      break;
    case TextureClass::Checkerboard:
      in[kTexOperandTex1] = value("tex1", 1.0f);
      in[kTexOperandTex2] = value("tex2", 0.0f);
      break;
    case TextureClass::Dots:
      // As every pbrt renders it (its constructor takes the two in the other order), and the reverse of the
      // documentation: "outside" fills the dots and "inside" the rest.
      in[kTexOperandDot] = value("outside", 0.0f);
      in[kTexOperandBackground] = value("inside", 1.0f);
      break;
    case TextureClass::Bilerp:
      in[kTexOperandV00] = constant("v00", 0.0f);
      in[kTexOperandV01] = constant("v01", 1.0f);
      in[kTexOperandV10] = constant("v10", 0.0f);
      in[kTexOperandV11] = constant("v11", 1.0f);
      break;
    default: break;
  }
}

void PbrtBuilder::make_texture(const std::string& name, const std::string& type, const std::string& cls,
                               const PbrtParams& ps, const Transform& to_world) {
  if (type != "float" && type != "spectrum")
    ps.fail(ps.line(), "texture type must be \"float\" or \"spectrum\", got " + in_quotes(type));
  const bool is_float = type == "float";
  if (textures_.count({name, is_float}))
    ps.fail(ps.line(), type + " texture " + in_quotes(name) + " is defined twice");
  if (cls == "ptex") {
    for (const PbrtParam& p : ps.params()) p.used = true;
    diag_.warn(ps, "ptex textures are not rendered (Kiln has no Ptex reader); parameters that use it keep their defaults");
    diag_.unsupported("ptex textures");
    textures_[{name, is_float}] = {-1, cls};
    return;
  }
  const auto info = std::find_if(kClasses.begin(), kClasses.end(), [&](const ClassInfo& c) { return cls == c.name; });
  if (info == kClasses.end())
    ps.fail(ps.line(), "unknown texture class " + in_quotes(cls) + " (" + class_list() + ")");
  if (!(is_float ? info->has_float : info->has_spectrum))
    ps.fail(ps.line(), "texture class " + in_quotes(cls) + " has no " + type + " textures");

  PbrtTextureDesc t;
  t.name = Error::format(ps.file(), ps.location(ps.line()), "");
  t.name.resize(t.name.size() - 2);  // without the ": " that would precede a message
  t.cls = info->cls;
  t.is_float = is_float;
  read_operands(ps, t);
  switch (t.cls) {
    case TextureClass::DirectionMix: {
      const Vec3f d = to_world.vector(ps.find_vector3("dir").value_or(Vec3f(0, 1, 0)));
      if (!(length(d) > 0.0f) || !is_finite(d)) ps.fail(ps.line(), "\"dir\" must be a non-zero vector");
      t.direction = normalize(d);
      break;
    }
    case TextureClass::Checkerboard:
      t.dimension = ps.get_int("dimension", 2);
      if (t.dimension != 2 && t.dimension != 3) ps.fail(ps.line(), "\"dimension\" must be 2 or 3");
      if (t.dimension == 2) read_mapping(ps, to_world, t.mapping);
      t.mapping.world_to_texture = to_world.inverse();
      break;
    case TextureClass::Dots:
    case TextureClass::Bilerp:
      read_mapping(ps, to_world, t.mapping);
      break;
    case TextureClass::ImageMap:
      read_mapping(ps, to_world, t.mapping);
      read_image_texture(ps, t.image);
      break;
    case TextureClass::Marble:
      t.marble_scale = ps.get_float("scale", 1.0f);
      t.variation = ps.get_float("variation", 0.2f);
      [[fallthrough]];
    case TextureClass::Fbm:
    case TextureClass::Wrinkled:
      t.octaves = ps.get_int("octaves", 8);
      t.roughness = ps.get_float("roughness", 0.5f);
      if (t.octaves < 0 || t.octaves > kPbrtMaxNoiseOctaves)
        ps.fail(ps.line(), "\"octaves\" must be in [0, " + std::to_string(kPbrtMaxNoiseOctaves) + "]");
      [[fallthrough]];
    case TextureClass::Windy:
      t.mapping.world_to_texture = to_world.inverse();
      break;
    default: break;
  }
  diag_.report_unused(ps);
  scene_.pbrt_textures.push_back(std::move(t));
  textures_[{name, is_float}] = {int(scene_.pbrt_textures.size()) - 1, cls};
}

}  // namespace kiln
