// Shapes' "alpha" (pbrt-v4: a float or a float texture on any shape): cut-outs, read into ShapeAlphaDesc
// (scenes/scene.h). Float "imagemap" textures are read here for it: filename, filter, wrap, encoding (pbrt's
// default: sRGB for PNG files, linear otherwise), scale, invert and the "uv" mapping's uscale, vscale, udelta, vdelta.
#include "scenes/pbrt/builder.h"

#include <filesystem>

#include "core/error.h"
#include "scenes/parse_util.h"

namespace kiln {
namespace {

TextureFilter filter_of(const PbrtParams& ps, const std::string& f) {
  if (f == "point") return TextureFilter::Nearest;
  if (f == "bilinear") return TextureFilter::Bilinear;
  if (f == "trilinear") return TextureFilter::Trilinear;
  if (f == "ewa" || f == "EWA") return TextureFilter::Ewa;
  ps.fail(ps.line(), "unknown \"filter\" " + in_quotes(f) + " (point, bilinear, trilinear, ewa)");
}

AlphaEncoding encoding_of(const PbrtParams& ps, const std::string& e, float& gamma) {
  if (e == "linear") return AlphaEncoding::Linear;
  if (e == "sRGB") return AlphaEncoding::Srgb;
  if (e.rfind("gamma ", 0) == 0) {
    const auto g = to_float(e.substr(6));
    if (g && *g > 0.0f) {
      gamma = *g;
      return AlphaEncoding::Gamma;
    }
  }
  ps.fail(ps.line(), "unknown \"encoding\" " + in_quotes(e) + " (linear, sRGB, \"gamma G\")");
}

}  // namespace

PbrtFloatImage PbrtBuilder::read_float_image(const std::string& name, const PbrtParams& ps) {
  PbrtFloatImage img;
  const auto file = ps.find_string("filename");
  if (!file) ps.fail(ps.line(), "needs \"string filename\"");
  img.texture.name = "Texture " + in_quotes(name) + " (" + std::filesystem::path(ps.file()).filename().string() +
                     ": line " + std::to_string(ps.line()) + ")";
  img.texture.source = TextureSource::Image;
  img.texture.image_path = resolve_(*file, ps);
  img.texture.filter = filter_of(ps, ps.get_string("filter", "bilinear"));
  if (ps.has("maxanisotropy")) ps.get_float("maxanisotropy", 8.0f);
  const std::string wrap = ps.get_string("wrap", "repeat");
  if (wrap == "clamp") {
    img.texture.wrap = TextureWrap::Clamp;
  } else if (wrap != "repeat") {
    diag_.warn(ps, "\"wrap\" " + in_quotes(wrap) + " is read as \"repeat\" for alpha");
  }
  const std::string ext = std::filesystem::path(*file).extension().string();
  const bool png = ext == ".png" || ext == ".PNG";
  img.lookup.encoding = encoding_of(ps, ps.get_string("encoding", png ? "sRGB" : "linear"), img.lookup.gamma);
  img.lookup.scale = ps.get_float("scale", 1.0f);
  img.lookup.invert = ps.get_bool("invert", false);
  if (const std::string mapping = ps.get_string("mapping", "uv"); mapping != "uv")
    diag_.warn(ps, "mapping " + in_quotes(mapping) + " is read as \"uv\" for alpha");
  img.lookup.su = ps.get_float("uscale", 1.0f);
  img.lookup.sv = ps.get_float("vscale", 1.0f);
  img.lookup.du = ps.get_float("udelta", 0.0f);
  img.lookup.dv = ps.get_float("vdelta", 0.0f);
  return img;
}

ShapeAlphaDesc PbrtBuilder::shape_alpha(const PbrtParams& ps) {
  ShapeAlphaDesc a;
  const auto tex = ps.find_texture("alpha");
  if (!tex) {
    a.value = ps.get_float("alpha", 1.0f);
    return a;
  }
  const auto it = textures_.find(*tex);
  if (it == textures_.end()) ps.fail(ps.line(), "no texture named " + in_quotes(*tex) + " (Texture defines them)");
  PbrtTextureDef& t = it->second;
  if (!t.is_float)
    ps.fail(ps.line(), "\"alpha\" names texture " + in_quotes(*tex) + ", a spectrum texture: alpha needs a float texture");
  if (t.value) {
    a.value = *t.value;
  } else if (t.float_image) {
    if (t.float_image->scene_texture < 0) {
      t.float_image->scene_texture = int(scene_.textures.size());
      scene_.textures.push_back(t.float_image->texture);
      scene_.external_files.push_back(t.float_image->texture.image_path);
    }
    a.texture = t.float_image->scene_texture;
    a.image = t.float_image->lookup;
  } else {
    diag_.warn(ps, "\"alpha\" uses texture " + in_quotes(*tex) + " (" + in_quotes(t.cls) +
                       "), which Kiln does not render for alpha; the shape is opaque");
    diag_.unsupported("alpha textures other than constant and imagemap");
  }
  return a;
}

}  // namespace kiln
