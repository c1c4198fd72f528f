#include "renderer/texture/texture_graph.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/error.h"
#include "core/math.h"
#include "renderer/texture/fractal_noise.h"
#include "core/perlin.h"

namespace kiln {
namespace {

// A checkerboard is blurred over a triangle filter this many footprints wide (pbrt-v4's).
constexpr float kCheckerFilterWidth = 1.5f;
// Dots: radius in cells; the noise is sampled at these offsets from a cell's corner to place and shift its dot.
constexpr float kDotRadius = 0.35f;
constexpr float kDotNoiseZ = 0.5f;
// Windy: the wind's strength varies ten times more slowly than the waves.
constexpr float kWindScale = 0.1f;
constexpr int kWindOctaves = 3, kWaveOctaves = 6;
constexpr float kWindyRoughness = 0.5f;
// Marble: the colour spline's control points (pbrt-v4's marble; 6 cubic Bezier segments) and its brightening.
constexpr Rgb kMarbleColours[] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f},
                                  {.5f, .5f, .5f},   {.6f, .59f, .58f}, {.58f, .58f, .6f},
                                  {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
constexpr float kMarbleGain = 1.5f;
// An imagemap's coarsest MIP level is read with this footprint (in texture widths).
constexpr float kWholeImageFootprint = 1e6f;

// c(x) = +1 on even cells [2k, 2k + 1), -1 on odd ones, averaged over a triangle filter of half-width r around x.
// With C the second antiderivative of c, the average is (C(x + r) - 2 C(x) + C(x - r)) / r^2; C(x) = x / 2 +
// y (1 - 2 |y|) with y = x / 2 - floor(x / 2) - 1/2 (x^2 / 2 on [0, 1], continuing with period 2 plus slope 1/2).
float filtered_checker(float x, float r) {
  if (std::floor(x - r) == std::floor(x + r)) return std::fmod(std::floor(x), 2.0f) != 0.0f ? -1.0f : 1.0f;
  const auto antiderivative2 = [](float v) {
    const float y = v / 2.0f - std::floor(v / 2.0f) - 0.5f;
    return v / 2.0f + y * (1.0f - 2.0f * std::fabs(y));
  };
  return (antiderivative2(x + r) - 2.0f * antiderivative2(x) + antiderivative2(x - r)) / (r * r);
}

float checker_weight_2d(const TexCoord2& c) {
  const float rs = kCheckerFilterWidth * std::max(std::fabs(c.dsdx), std::fabs(c.dsdy));
  const float rt = kCheckerFilterWidth * std::max(std::fabs(c.dtdx), std::fabs(c.dtdy));
  return 0.5f - 0.5f * filtered_checker(c.st.x, rs) * filtered_checker(c.st.y, rt);
}

float checker_weight_3d(const TexCoord3& c) {
  float product = 1.0f;
  for (int a = 0; a < 3; ++a)
    product *= filtered_checker(c.p[a], kCheckerFilterWidth * std::max(std::fabs(c.dpdx[a]), std::fabs(c.dpdy[a])));
  return 0.5f - 0.5f * product;
}

bool inside_dot(Vec2f st) {
  const float s_cell = std::floor(st.x + 0.5f), t_cell = std::floor(st.y + 0.5f);
  if (!(course_perlin({s_cell + 0.5f, t_cell + 0.5f, kDotNoiseZ}) > 0.0f)) return false;
  const float max_shift = 0.5f - kDotRadius;
  const float s_centre = s_cell + max_shift * course_perlin({s_cell + 1.5f, t_cell + 2.8f, kDotNoiseZ});
  const float t_centre = t_cell + max_shift * course_perlin({s_cell + 4.5f, t_cell + 9.8f, kDotNoiseZ});
  return sqr(st.x - s_centre) + sqr(st.y - t_centre) < sqr(kDotRadius);
}

Rgb marble_colour(float t) {
  constexpr int kSegments = int(std::size(kMarbleColours)) - 3;
  const int first = std::clamp(int(std::floor(t * float(kSegments))), 0, kSegments - 1);
  const float u = t * float(kSegments) - float(first);
  // De Casteljau on the segment's four control points.
  Rgb p[4] = {kMarbleColours[first], kMarbleColours[first + 1], kMarbleColours[first + 2], kMarbleColours[first + 3]};
  for (int level = 3; level > 0; --level)
    for (int k = 0; k < level; ++k) p[k] = p[k] * (1.0f - u) + p[k + 1] * u;
  return p[0] * kMarbleGain;
}

// Past an edge of an octahedral sphere map the sphere continues on the mirrored side.
void fold_octahedral(float& s, float& t) {
  for (int pass = 0; pass < 2; ++pass) {
    if (s < 0.0f) s = -s, t = 1.0f - t;
    if (s > 1.0f) s = 2.0f - s, t = 1.0f - t;
    if (t < 0.0f) t = -t, s = 1.0f - s;
    if (t > 1.0f) t = 2.0f - t, s = 1.0f - s;
  }
}

TextureInterp interp_of(ImageFilter f) {
  switch (f) {
    case ImageFilter::Point: return TextureInterp::ClosestOneLevel;
    case ImageFilter::Bilinear: return TextureInterp::BilinearOneLevel;
    case ImageFilter::Trilinear: return TextureInterp::Trilinear;
    case ImageFilter::Ewa: return TextureInterp::Anisotropic;
  }
  return TextureInterp::BilinearOneLevel;
}

TextureWrapMode wrap_of(ImageWrap w) {
  switch (w) {
    case ImageWrap::Repeat: return TextureWrapMode::Periodic;
    case ImageWrap::Black: return TextureWrapMode::Black;
    case ImageWrap::Clamp:
    case ImageWrap::OctahedralSphere: return TextureWrapMode::Clamp;  // folded into [0, 1]^2 before the lookup
  }
  return TextureWrapMode::Periodic;
}

// pbrt-v4 reads colour channels as stored, whatever the alpha.
TextureDecode decode_of(const ImageTextureDesc& d) {
  switch (d.encoding) {
    case ImageEncoding::Linear: return {TextureDecodeKind::Linear, 1.0f, true};
    case ImageEncoding::Srgb: return {TextureDecodeKind::Srgb, 1.0f, true};
    case ImageEncoding::Gamma: return {TextureDecodeKind::Gamma, d.gamma, true};
  }
  return {};
}

template <typename T>
T zero() {
  if constexpr (std::is_same_v<T, float>)
    return 0.0f;
  else
    return Rgb(0.0f);
}

// (1 - w) a + w b, evaluating each side only where its weight is not zero.
template <typename T, typename A, typename B>
T blend(float w, A&& a, B&& b) {
  const T ta = w != 1.0f ? a() : zero<T>();
  const T tb = w != 0.0f ? b() : zero<T>();
  return ta * (1.0f - w) + tb * w;
}

}  // namespace

TextureGraph::TextureGraph(const std::vector<PbrtTextureDesc>& textures, const std::string& scene_file,
                           TextureImages& images)
    : scene_file_(scene_file), images_(images) {
  nodes_.reserve(textures.size());
  for (const PbrtTextureDesc& d : textures) nodes_.push_back(Node{d, {}, false, false});
  stats_.defined = textures.size();
}

void TextureGraph::open_image(Node& n) {
  const ImageTextureDesc& d = n.desc.image;
  const OpenedImage img = images_.open(d.path, decode_of(d), n.desc.name, "imagemap");
  n.image.handle = img.handle;
  n.image.channels = img.info.channels;
  n.image.query.interp = interp_of(d.filter);
  n.image.query.wrap = wrap_of(d.wrap);
  if (n.desc.is_float && n.image.channels >= 4) {
    // The average over the whole image (its coarsest level) is 1 only when every texel's alpha is.
    TextureQuery whole = n.image.query;
    whole.interp = TextureInterp::BilinearOneLevel;
    whole.dsdx = whole.dtdy = kWholeImageFootprint;
    float rgba[4];
    images_.lookup(n.image.handle, whole, rgba);
    n.image.opaque_alpha = rgba[3] >= 1.0f;
  }
  ++stats_.images;
}

void TextureGraph::use(int i) {
  Node& n = nodes_[size_t(i)];
  if (n.compiled) return;
  n.compiled = true;
  ++stats_.compiled;
  bool footprint = false;
  for (const TexturedRgb& o : n.desc.operands)
    if (o.textured()) {
      use(o.texture);
      footprint = footprint || nodes_[size_t(o.texture)].needs_footprint;
    }
  switch (n.desc.cls) {
    case TextureClass::ImageMap:
      open_image(n);
      footprint = true;
      break;
    case TextureClass::Checkerboard:
    case TextureClass::Fbm:
    case TextureClass::Wrinkled:
    case TextureClass::Windy:
    case TextureClass::Marble:
      footprint = true;
      break;
    default: break;
  }
  n.needs_footprint = footprint;
}

template <typename T>
T TextureGraph::operand(const TexturedRgb& o, const TextureEvalContext& c) const {
  if (o.textured()) return eval<T>(o.texture, c);
  if constexpr (std::is_same_v<T, float>)
    return o.value.r;
  else
    return o.value;
}

template <typename T>
T TextureGraph::image_value(const Node& n, const TextureEvalContext& c) const {
  const TexCoord2 tc = map_2d(n.desc.mapping, c);
  TextureQuery q = n.image.query;
  q.s = tc.st.x;
  q.t = 1.0f - tc.st.y;
  q.dsdx = tc.dsdx, q.dsdy = tc.dsdy, q.dtdx = -tc.dtdx, q.dtdy = -tc.dtdy;
  if (n.desc.image.wrap == ImageWrap::OctahedralSphere) fold_octahedral(q.s, q.t);
  float v[4];
  images_.lookup(n.image.handle, q, v);
  const ImageTextureDesc& d = n.desc.image;
  const int ch = n.image.channels;
  if constexpr (std::is_same_v<T, float>) {
    float x = ch == 1 ? v[0] : ch == 2 ? v[1] : (ch >= 4 && !n.image.opaque_alpha) ? v[3] : (v[0] + v[1] + v[2]) / 3.0f;
    x *= d.scale;
    return d.invert ? std::max(0.0f, 1.0f - x) : x;
  } else {
    Rgb x = ch < 3 ? Rgb(v[0]) : Rgb(v[0], v[1], v[2]);
    x *= d.scale;
    if (d.invert) x = Rgb(1.0f) - x;
    return Rgb(std::max(x.r, 0.0f), std::max(x.g, 0.0f), std::max(x.b, 0.0f));
  }
}

template <typename T>
T TextureGraph::noise_value(const Node& n, const TextureEvalContext& c) const {
  const PbrtTextureDesc& d = n.desc;
  TexCoord3 tc = map_3d(d.mapping.world_to_texture, c);
  if constexpr (std::is_same_v<T, float>) {
    switch (d.cls) {
      case TextureClass::Fbm: return fbm(tc.p, tc.dpdx, tc.dpdy, d.roughness, d.octaves);
      case TextureClass::Wrinkled: return turbulence(tc.p, tc.dpdx, tc.dpdy, d.roughness, d.octaves);
      case TextureClass::Windy: {
        const float wind = fbm(tc.p * kWindScale, tc.dpdx * kWindScale, tc.dpdy * kWindScale, kWindyRoughness,
                               kWindOctaves);
        return std::fabs(wind) * fbm(tc.p, tc.dpdx, tc.dpdy, kWindyRoughness, kWaveOctaves);
      }
      default: return 0.0f;
    }
  } else {
    if (d.cls != TextureClass::Marble) return Rgb(0.0f);
    tc.p = tc.p * d.marble_scale;
    const float m = tc.p.y + d.variation * fbm(tc.p, tc.dpdx * d.marble_scale, tc.dpdy * d.marble_scale, d.roughness,
                                               d.octaves);
    return marble_colour(0.5f + 0.5f * std::sin(m));
  }
}

template <typename T>
T TextureGraph::eval(int i, const TextureEvalContext& c) const {
  const Node& n = nodes_[size_t(i)];
  const PbrtTextureDesc& d = n.desc;
  const auto& in = d.operands;
  const auto arg = [&](int k) { return [&, k] { return operand<T>(in[size_t(k)], c); }; };
  switch (d.cls) {
    case TextureClass::Constant: return operand<T>(in[0], c);
    case TextureClass::Scale: {
      const float s = operand<float>(in[kTexOperandScale], c);
      return s == 0.0f ? zero<T>() : operand<T>(in[kTexOperandTex], c) * s;
    }
    case TextureClass::Mix:
      return blend<T>(operand<float>(in[kTexOperandAmount], c), arg(kTexOperandTex1), arg(kTexOperandTex2));
    case TextureClass::DirectionMix:  // weight |n . dir| on tex1
      return blend<T>(1.0f - std::fabs(dot(c.n, d.direction)), arg(kTexOperandTex1), arg(kTexOperandTex2));
    case TextureClass::Checkerboard: {
      const float w = d.dimension == 2 ? checker_weight_2d(map_2d(d.mapping, c))
                                       : checker_weight_3d(map_3d(d.mapping.world_to_texture, c));
      return blend<T>(w, arg(kTexOperandTex1), arg(kTexOperandTex2));
    }
    case TextureClass::Dots:
      return inside_dot(map_2d(d.mapping, c).st) ? operand<T>(in[kTexOperandDot], c)
                                                  : operand<T>(in[kTexOperandBackground], c);
    case TextureClass::Bilerp: {
      const Vec2f st = map_2d(d.mapping, c).st;
      return operand<T>(in[kTexOperandV00], c) * ((1 - st.x) * (1 - st.y)) +
             operand<T>(in[kTexOperandV10], c) * (st.x * (1 - st.y)) +
             operand<T>(in[kTexOperandV01], c) * ((1 - st.x) * st.y) + operand<T>(in[kTexOperandV11], c) * (st.x * st.y);
    }
    case TextureClass::ImageMap: return image_value<T>(n, c);
    case TextureClass::Fbm:
    case TextureClass::Wrinkled:
    case TextureClass::Windy:
    case TextureClass::Marble: return noise_value<T>(n, c);
  }
  return zero<T>();
}

float TextureGraph::eval_float(int i, const TextureEvalContext& c) const { return eval<float>(i, c); }
Rgb TextureGraph::eval_rgb(int i, const TextureEvalContext& c) const { return eval<Rgb>(i, c); }

}  // namespace kiln
