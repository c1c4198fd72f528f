// pbrt-v4 texture classes (renderer/texture/texture_graph.h) against their definitions at known (u, v) and points:
// constant, scale, mix (constant and textured amount), directionmix, 2-D and 3-D checkerboards (sharp, and filtered
// against a numerical integral of the triangle filter), dots (discs of radius 0.35), bilerp, the uv / spherical /
// cylindrical / planar mappings, fbm / wrinkled / windy as sums of octaves, marble's spline ends; imagemaps on
// small files written here: the v flip, point and bilinear lookups, sRGB / gamma decoding before filtering, scale,
// invert, the wrap modes, and the channel rules of float textures.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/error.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render_util.h"
#include "renderer/texture/fractal_noise.h"
#include "core/perlin.h"
#include "renderer/texture/texture_graph.h"

namespace kiln::test {
namespace {

PbrtTextureDesc texture(TextureClass cls, bool is_float, std::initializer_list<TexturedRgb> operands = {}) {
  PbrtTextureDesc t;
  t.name = "test.pbrt: line 1 (Texture)";
  t.cls = cls;
  t.is_float = is_float;
  size_t i = 0;
  for (const TexturedRgb& o : operands) t.operands[i++] = o;
  return t;
}

TexturedRgb f(float v) { return TexturedRgb(Rgb(v)); }
TexturedRgb tex(int i) { return TexturedRgb(Rgb(0.0f), i); }

// A graph over `textures` with every texture compiled.
struct Graph {
  TextureImages images{TextureSystemOptions{}};
  TextureGraph graph;
  explicit Graph(const std::vector<PbrtTextureDesc>& t) : graph(t, "test.pbrt", images) {
    for (size_t i = 0; i < t.size(); ++i) graph.use(int(i));
  }
};

TextureEvalContext at_uv(float u, float v) {
  TextureEvalContext c;
  c.uv = {u, v};
  c.n = {0, 0, 1};
  return c;
}
TextureEvalContext at_point(Vec3f p) {
  TextureEvalContext c;
  c.p = p;
  c.n = {0, 0, 1};
  return c;
}

// A float bilerp that returns s (or t): the mapping's coordinates made visible.
PbrtTextureDesc coordinate(int axis, TextureMappingDesc m) {
  PbrtTextureDesc t = axis == 0 ? texture(TextureClass::Bilerp, true, {f(0), f(0), f(1), f(1)})
                                : texture(TextureClass::Bilerp, true, {f(0), f(1), f(0), f(1)});
  t.mapping = m;
  return t;
}

TEST(PbrtTextureClasses, ConstantScaleMix) {
  Graph g({texture(TextureClass::Constant, false, {TexturedRgb(Rgb(0.2f, 0.4f, 0.6f))}),     // 0
           texture(TextureClass::Scale, false, {tex(0), f(2.5f)}),                          // 1
           texture(TextureClass::Scale, false, {tex(0), f(0.0f)}),                          // 2
           coordinate(0, {}),                                                               // 3: amount = u
           texture(TextureClass::Mix, false, {TexturedRgb(Rgb(1, 0, 0)), tex(0), tex(3)}),  // 4
           texture(TextureClass::Mix, true, {f(2.0f), f(6.0f), f(0.25f)})});                // 5
  const TextureEvalContext c = at_uv(0.3f, 0.8f);
  EXPECT_EQ(g.graph.eval_rgb(0, c), Rgb(0.2f, 0.4f, 0.6f));
  const Rgb scaled = g.graph.eval_rgb(1, c);
  EXPECT_FLOAT_EQ(scaled.r, 0.5f);
  EXPECT_FLOAT_EQ(scaled.b, 1.5f);
  EXPECT_EQ(g.graph.eval_rgb(2, c), Rgb(0.0f));
  const Rgb mixed = g.graph.eval_rgb(4, c);  // (1 - u) red + u (0.2, 0.4, 0.6)
  EXPECT_NEAR(mixed.r, 0.7f * 1.0f + 0.3f * 0.2f, 1e-6f);
  EXPECT_NEAR(mixed.g, 0.3f * 0.4f, 1e-6f);
  EXPECT_NEAR(mixed.b, 0.3f * 0.6f, 1e-6f);
  EXPECT_FLOAT_EQ(g.graph.eval_float(5, c), 0.75f * 2.0f + 0.25f * 6.0f);
}

TEST(PbrtTextureClasses, DirectionMixWeighsTex1ByTheNormalsCosine) {
  PbrtTextureDesc d = texture(TextureClass::DirectionMix, true, {f(10.0f), f(2.0f)});
  d.direction = normalize(Vec3f(1, 0, 1));
  Graph g({d});
  TextureEvalContext c = at_uv(0, 0);
  const float a = std::sqrt(0.5f);
  EXPECT_NEAR(g.graph.eval_float(0, c), a * 10.0f + (1 - a) * 2.0f, 1e-5f);
  c.n = {0, 0, -1};  // either side of the surface
  EXPECT_NEAR(g.graph.eval_float(0, c), a * 10.0f + (1 - a) * 2.0f, 1e-5f);
  c.n = {0, 1, 0};
  EXPECT_FLOAT_EQ(g.graph.eval_float(0, c), 2.0f);
}

TEST(PbrtTextureClasses, CheckerboardCellsWithoutFootprint) {
  PbrtTextureDesc two = texture(TextureClass::Checkerboard, true, {f(1.0f), f(0.0f)});
  two.mapping.su = 4.0f;
  two.mapping.sv = 2.0f;
  PbrtTextureDesc three = texture(TextureClass::Checkerboard, true, {f(1.0f), f(0.0f)});
  three.dimension = 3;
  three.mapping.world_to_texture = Transform::scale(Vec3f(2.0f));
  Graph g({two, three});
  for (float u = -0.97f; u < 1.0f; u += 0.0731f)
    for (float v = -0.97f; v < 1.0f; v += 0.0893f) {
      const bool even = (int64_t(std::floor(4 * u)) + int64_t(std::floor(2 * v))) % 2 == 0;
      EXPECT_EQ(g.graph.eval_float(0, at_uv(u, v)), even ? 1.0f : 0.0f) << u << " " << v;
      const Vec3f p(u, v, 0.37f * u - 0.61f * v);
      const bool even3 = (int64_t(std::floor(2 * p.x)) + int64_t(std::floor(2 * p.y)) + int64_t(std::floor(2 * p.z))) % 2 == 0;
      EXPECT_EQ(g.graph.eval_float(1, at_point(p)), even3 ? 1.0f : 0.0f) << p.x << " " << p.y << " " << p.z;
    }
}

// With a footprint, the weight of tex2 is the checker averaged over a triangle filter of half-width 1.5 footprints
// (separable in s and t): checked against a numerical integral.
TEST(PbrtTextureClasses, CheckerboardIsTheTriangleFilteredChecker) {
  Graph g({texture(TextureClass::Checkerboard, true, {f(1.0f), f(0.0f)})});
  const auto checker = [](double x) { return (int64_t(std::floor(x)) & 1) ? -1.0 : 1.0; };
  const auto filtered = [&](double x, double r) {
    double sum = 0, wsum = 0;
    for (int i = -4000; i <= 4000; ++i) {
      const double t = r * i / 4000.0, w = 1.0 - std::fabs(t) / r;
      sum += w * checker(x + t);
      wsum += w;
    }
    return sum / wsum;
  };
  const struct {
    float u, v, du, dv;
  } cases[] = {{0.9f, 0.3f, 0.2f, 0.01f}, {2.05f, -0.5f, 0.1f, 0.3f}, {-1.3f, 7.95f, 0.5f, 0.08f},
               {0.5f, 0.5f, 0.01f, 0.01f}};
  for (const auto& k : cases) {
    TextureEvalContext c = at_uv(k.u, k.v);
    c.fp.dudx = k.du;
    c.fp.dvdy = -k.dv;
    const double w = 0.5 - 0.5 * filtered(k.u, 1.5 * k.du) * filtered(k.v, 1.5 * k.dv);  // tex2's weight
    EXPECT_NEAR(g.graph.eval_float(0, c), 1.0 - w, 2e-3) << k.u << " " << k.v;
  }
}

// Every cell holds either no dot or one disc of radius 0.35 (area pi 0.35^2), inside which the texture is `inside`.
TEST(PbrtTextureClasses, DotsAreDiscsOfRadiusPointThreeFive) {
  Graph g({texture(TextureClass::Dots, true, {f(1.0f), f(0.0f)})});
  int with_dots = 0;
  constexpr int kGrid = 200;
  for (int cell = 0; cell < 40; ++cell) {
    const float s0 = float(cell % 8) - 0.5f, t0 = float(cell / 8) - 0.5f;  // the cell around (cell % 8, cell / 8)
    int inside = 0;
    for (int i = 0; i < kGrid; ++i)
      for (int j = 0; j < kGrid; ++j) {
        const float v = g.graph.eval_float(0, at_uv(s0 + (i + 0.5f) / kGrid, t0 + (j + 0.5f) / kGrid));
        ASSERT_TRUE(v == 0.0f || v == 1.0f);
        inside += v == 1.0f;
      }
    const double fraction = double(inside) / (kGrid * kGrid);
    if (inside > 0) {
      ++with_dots;
      EXPECT_NEAR(fraction, kPi * 0.35 * 0.35, 0.01) << "cell " << cell;
    }
  }
  EXPECT_GT(with_dots, 5);
  EXPECT_LT(with_dots, 40);
}

TEST(PbrtTextureClasses, BilerpAndTheMappings) {
  TextureMappingDesc uv;
  uv.su = 2.0f, uv.sv = 3.0f, uv.du = 0.5f, uv.dv = -1.0f;
  TextureMappingDesc sphere;
  sphere.kind = TextureMapping::Spherical;
  sphere.world_to_texture = Transform::translate({0, 0, -1});
  TextureMappingDesc cylinder;
  cylinder.kind = TextureMapping::Cylindrical;
  TextureMappingDesc planar;
  planar.kind = TextureMapping::Planar;
  planar.v1 = {0, 1, 0}, planar.v2 = {0, 0, 2}, planar.du = 0.25f, planar.dv = 0.5f;
  Graph g({texture(TextureClass::Bilerp, true, {f(1), f(2), f(3), f(4)}), coordinate(0, uv), coordinate(1, uv),
           coordinate(0, sphere), coordinate(1, sphere), coordinate(0, cylinder), coordinate(1, cylinder),
           coordinate(0, planar), coordinate(1, planar)});
  // bilerp: v00 = 1, v01 = 2, v10 = 3, v11 = 4 at (s, t) = (0.25, 0.75).
  EXPECT_FLOAT_EQ(g.graph.eval_float(0, at_uv(0.25f, 0.75f)),
                  0.75f * 0.25f * 1 + 0.75f * 0.75f * 2 + 0.25f * 0.25f * 3 + 0.25f * 0.75f * 4);
  EXPECT_FLOAT_EQ(g.graph.eval_float(1, at_uv(0.3f, 0.6f)), 2 * 0.3f + 0.5f);
  EXPECT_FLOAT_EQ(g.graph.eval_float(2, at_uv(0.3f, 0.6f)), 3 * 0.6f - 1.0f);
  // spherical about (0, 0, 1): s = theta / pi from +z, t = phi / 2 pi.
  const Vec3f p = Vec3f(0, 0, 1) + normalize(Vec3f(-1, -1, 0)) * 2.0f;
  EXPECT_NEAR(g.graph.eval_float(3, at_point(p)), 0.5f, 1e-6f);
  EXPECT_NEAR(g.graph.eval_float(4, at_point(p)), 0.625f, 1e-6f);
  EXPECT_NEAR(g.graph.eval_float(3, at_point({0, 0, 3})), 0.0f, 1e-6f);
  // cylindrical: s = (pi + atan2(y, x)) / 2 pi, t = z.
  EXPECT_NEAR(g.graph.eval_float(5, at_point({0, 1, 7})), 0.75f, 1e-6f);
  EXPECT_NEAR(g.graph.eval_float(6, at_point({0, 1, 7})), 7.0f, 1e-6f);
  // planar: s = du + p . v1, t = dv + p . v2.
  EXPECT_FLOAT_EQ(g.graph.eval_float(7, at_point({5, 0.5f, 0.2f})), 0.75f);
  EXPECT_FLOAT_EQ(g.graph.eval_float(8, at_point({5, 0.5f, 0.2f})), 0.9f);
}

// ---- noise ---------------------------------------------------------------------------------------------------------

double octave_sum(Vec3f p, float omega, int octaves, bool absolute) {
  double sum = 0, amplitude = 1, frequency = 1;
  for (int i = 0; i < octaves; ++i) {
    const double n = course_perlin(p * float(frequency));
    sum += amplitude * (absolute ? std::fabs(n) : n);
    amplitude *= omega;
    frequency *= 1.99;
  }
  return sum;
}

TEST(PbrtTextureClasses, NoiseTexturesAreSumsOfOctaves) {
  PbrtTextureDesc fbm = texture(TextureClass::Fbm, true);
  fbm.octaves = 6, fbm.roughness = 0.6f;
  fbm.mapping.world_to_texture = Transform::scale(Vec3f(3.0f));
  PbrtTextureDesc wrinkled = texture(TextureClass::Wrinkled, true);
  wrinkled.octaves = 5, wrinkled.roughness = 0.4f;
  PbrtTextureDesc windy = texture(TextureClass::Windy, true);
  Graph g({fbm, wrinkled, windy});
  for (const Vec3f p : {Vec3f(0.37f, -1.2f, 2.9f), Vec3f(10.1f, 3.3f, -0.45f), Vec3f(-7.7f, 0.05f, 1.5f)}) {
    // No footprint: every octave.
    EXPECT_NEAR(g.graph.eval_float(0, at_point(p)), octave_sum(p * 3.0f, 0.6f, 6, false), 1e-5);
    // Turbulence adds the average 0.2 omega^octaves of the (fully faded) octave past the last.
    EXPECT_NEAR(g.graph.eval_float(1, at_point(p)), octave_sum(p, 0.4f, 5, true) + 0.2 * std::pow(0.4, 5), 1e-5);
    EXPECT_NEAR(g.graph.eval_float(2, at_point(p)),
                std::fabs(octave_sum(p * 0.1f, 0.5f, 3, false)) * octave_sum(p, 0.5f, 6, false), 1e-5);
    // A footprint of 2^-3 resolves 2 octaves (-1 - log2(1/8)): fbm sums two, turbulence adds 0.2 omega^i for the rest.
    TextureEvalContext c = at_point(p);
    c.dpdx = {0.125f / 3.0f, 0, 0};  // 1/8 in fbm's texture space (scaled 3x)
    EXPECT_NEAR(g.graph.eval_float(0, c), octave_sum(p * 3.0f, 0.6f, 2, false), 1e-5);
    c.dpdx = {0.125f, 0, 0};
    double rest = 0.2 * std::pow(0.4, 2);  // the faded octave 2, then the average for octaves 2..4
    for (int i = 2; i < 5; ++i) rest += 0.2 * std::pow(0.4, i);
    EXPECT_NEAR(g.graph.eval_float(1, c), octave_sum(p, 0.4f, 2, true) + rest, 1e-5);
  }
}

TEST(PbrtTextureClasses, MarbleFollowsItsColourSpline) {
  PbrtTextureDesc m = texture(TextureClass::Marble, false);
  m.variation = 0.0f;  // marble = y: t = 1/2 + sin(y) / 2 runs the spline from its first to its last point
  Graph g({m});
  const Rgb first = g.graph.eval_rgb(0, at_point({0.3f, -kPi / 2, 0.1f}));
  EXPECT_NEAR(first.r, 1.5f * 0.58f, 1e-5f);
  EXPECT_NEAR(first.b, 1.5f * 0.6f, 1e-5f);
  const Rgb middle = g.graph.eval_rgb(0, at_point({0.3f, 0.0f, 0.1f}));  // t = 1/2: the fourth control point
  EXPECT_NEAR(middle.r, 1.5f * 0.5f, 1e-5f);
  const Rgb last = g.graph.eval_rgb(0, at_point({0.3f, kPi / 2, 0.1f}));
  EXPECT_NEAR(last.g, 1.5f * 0.58f, 1e-5f);
}

// ---- images --------------------------------------------------------------------------------------------------------

std::string image_dir() { return tmp_dir("pbrt_textures"); }

PbrtTextureDesc imagemap(const std::string& path, bool is_float, ImageFilter filter = ImageFilter::Point,
                         ImageEncoding encoding = ImageEncoding::Linear) {
  PbrtTextureDesc t = texture(TextureClass::ImageMap, is_float);
  t.image.path = path;
  t.image.filter = filter;
  t.image.encoding = encoding;
  return t;
}

// The texel column x and row y (y = 0 the top row) of a W x H image at the uv of its centre: v runs up.
TextureEvalContext texel_centre(int x, int y, int w, int h) {
  return at_uv((float(x) + 0.5f) / float(w), 1.0f - (float(y) + 0.5f) / float(h));
}

// A binary PGM (P5): grey, 8 or 16 bit (big-endian), as OpenImageIO reads it.
std::string write_pgm(const std::string& name, int w, int h, const std::vector<int>& values, int maxval) {
  const std::string path = image_dir() + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out << "P5\n" << w << " " << h << "\n" << maxval << "\n";
  for (int v : values) {
    if (maxval > 255) out.put(char((v >> 8) & 0xff));
    out.put(char(v & 0xff));
  }
  return path;
}

// An uncompressed 32-bit TGA (top-left origin), texels given as RGBA bytes.
std::string write_tga(const std::string& name, int w, int h, const std::vector<std::array<int, 4>>& rgba) {
  const std::string path = image_dir() + "/" + name;
  std::ofstream out(path, std::ios::binary);
  const unsigned char header[18] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, (unsigned char)(w & 0xff),
                                    (unsigned char)(w >> 8), (unsigned char)(h & 0xff), (unsigned char)(h >> 8),
                                    32, 0x28};
  out.write(reinterpret_cast<const char*>(header), 18);
  for (const auto& p : rgba) out << char(p[2]) << char(p[1]) << char(p[0]) << char(p[3]);
  return path;
}

double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

TEST(PbrtImageTextures, TexelsAreLookedUpWithVRunningUp) {
  Image img(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) img.at(x, y) = Rgb(float(x), float(y), 0.25f);
  const std::string path = image_dir() + "/grid.exr";
  write_exr(path, img, {}, {});
  PbrtTextureDesc scaled = imagemap(path, false);
  scaled.image.scale = 2.0f;
  PbrtTextureDesc inverted = imagemap(path, true);
  inverted.image.invert = true;
  inverted.image.scale = 0.5f;
  Graph g({imagemap(path, false), imagemap(path, true), scaled, inverted});
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      const TextureEvalContext c = texel_centre(x, y, 4, 3);
      EXPECT_EQ(g.graph.eval_rgb(0, c), img.at(x, y)) << x << "," << y;
      EXPECT_FLOAT_EQ(g.graph.eval_float(1, c), (float(x) + float(y) + 0.25f) / 3.0f);  // RGB: the average
      EXPECT_EQ(g.graph.eval_rgb(2, c), img.at(x, y) * 2.0f);
      EXPECT_FLOAT_EQ(g.graph.eval_float(3, c), std::max(0.0f, 1.0f - 0.5f * (float(x) + float(y) + 0.25f) / 3.0f));
    }
}

// 8-bit files are decoded (sRGB, gamma) per texel before the bilinear filter mixes them, as pbrt-v4 decodes at load.
TEST(PbrtImageTextures, EncodingsDecodeBeforeFiltering) {
  const std::string path = image_dir() + "/two.png";
  write_png(path, {0, 128, 255, 255, 64, 0}, 2, 1);
  PbrtTextureDesc gamma = imagemap(path, false, ImageFilter::Point, ImageEncoding::Gamma);
  gamma.image.gamma = 1.8f;
  Graph g({imagemap(path, false, ImageFilter::Point, ImageEncoding::Srgb),
           imagemap(path, false, ImageFilter::Point, ImageEncoding::Linear), gamma,
           imagemap(path, false, ImageFilter::Bilinear, ImageEncoding::Srgb)});
  const TextureEvalContext left = texel_centre(0, 0, 2, 1), right = texel_centre(1, 0, 2, 1);
  const Rgb srgb = g.graph.eval_rgb(0, left);
  EXPECT_NEAR(srgb.g, srgb_to_linear(128.0 / 255.0), 1e-6);
  EXPECT_NEAR(srgb.b, 1.0, 1e-6);
  EXPECT_NEAR(g.graph.eval_rgb(0, right).g, srgb_to_linear(64.0 / 255.0), 1e-6);
  EXPECT_NEAR(g.graph.eval_rgb(1, left).g, 128.0 / 255.0, 1e-6);
  EXPECT_NEAR(g.graph.eval_rgb(2, left).g, std::pow(128.0 / 255.0, 1.8), 1e-6);
  // Halfway between the texel centres: the mean of the decoded values (red 0 and 1: 0.5, not decode(0.5) = 0.21).
  const Rgb mid = g.graph.eval_rgb(3, at_uv(0.5f, 0.5f));
  EXPECT_NEAR(mid.r, 0.5, 1e-5);
  EXPECT_NEAR(mid.g, 0.5 * (srgb_to_linear(128.0 / 255.0) + srgb_to_linear(64.0 / 255.0)), 1e-5);
}

TEST(PbrtImageTextures, WrapModes) {
  Image img(4, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) img.at(x, y) = Rgb(float(1 + x + 4 * y));
  const std::string path = image_dir() + "/wrap.exr";
  write_exr(path, img, {}, {});
  std::vector<PbrtTextureDesc> t;
  for (ImageWrap w : {ImageWrap::Repeat, ImageWrap::Black, ImageWrap::Clamp, ImageWrap::OctahedralSphere}) {
    t.push_back(imagemap(path, true));
    t.back().image.wrap = w;
  }
  Graph g(t);
  const TextureEvalContext left_of_0 = at_uv(-0.125f, 0.25f);  // one texel left of texel (0, 1)
  EXPECT_FLOAT_EQ(g.graph.eval_float(0, left_of_0), img.at(3, 1).r);
  EXPECT_FLOAT_EQ(g.graph.eval_float(1, left_of_0), 0.0f);
  EXPECT_FLOAT_EQ(g.graph.eval_float(2, left_of_0), img.at(0, 1).r);
  // Octahedral: past the left edge the map continues mirrored, on the other half vertically: (0.125, 0.75).
  EXPECT_FLOAT_EQ(g.graph.eval_float(3, left_of_0), img.at(0, 0).r);
  EXPECT_FLOAT_EQ(g.graph.eval_float(3, at_uv(0.375f, 1.25f)), img.at(2, 0).r);
  EXPECT_FLOAT_EQ(g.graph.eval_float(0, at_uv(0.375f + 3.0f, 0.75f - 2.0f)), img.at(1, 0).r);
}

TEST(PbrtImageTextures, ChannelRulesOfFloatAndSpectrumTextures) {
  // Grey 8- and 16-bit files: the value in all three channels; sRGB decoding applies to 16 bits too.
  const std::string grey = write_pgm("grey.pgm", 2, 1, {51, 204}, 255);
  const std::string grey16 = write_pgm("grey16.pgm", 1, 1, {30000}, 65535);
  // RGBA: a float texture reads alpha, unless alpha is 1 everywhere (then the channel average). Colour channels are
  // as stored, not multiplied by alpha.
  const std::string rgba = write_tga("rgba.tga", 2, 1, {{{255, 0, 0, 51}}, {{0, 102, 255, 255}}});
  const std::string opaque = write_tga("opaque.tga", 1, 1, {{{255, 51, 0, 255}}});
  Graph g({imagemap(grey, false), imagemap(grey, true), imagemap(grey16, true, ImageFilter::Point, ImageEncoding::Srgb),
           imagemap(rgba, true), imagemap(rgba, false), imagemap(opaque, true)});
  EXPECT_NEAR(g.graph.eval_rgb(0, texel_centre(1, 0, 2, 1)).b, 0.8f, 1e-6f);
  EXPECT_NEAR(g.graph.eval_float(1, texel_centre(0, 0, 2, 1)), 0.2f, 1e-6f);
  EXPECT_NEAR(g.graph.eval_float(2, at_uv(0.5f, 0.5f)), srgb_to_linear(30000.0 / 65535.0), 1e-5);
  EXPECT_NEAR(g.graph.eval_float(3, texel_centre(0, 0, 2, 1)), 0.2f, 1e-6f);
  EXPECT_NEAR(g.graph.eval_rgb(4, texel_centre(0, 0, 2, 1)).r, 1.0f, 1e-6f);
  EXPECT_NEAR(g.graph.eval_float(5, at_uv(0.5f, 0.5f)), (1.0f + 0.2f) / 3.0f, 1e-6f);
}

TEST(PbrtImageTextures, AnUnreadableImageNamesTheTexture) {
  const std::string path = image_dir() + "/broken.png";
  std::ofstream(path, std::ios::binary) << "not a png";
  TextureImages images{TextureSystemOptions{}};
  TextureGraph graph({imagemap(path, false)}, "test.pbrt", images);
  try {
    graph.use(0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.pbrt: line 1 (Texture)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("broken.png"), std::string::npos) << e.what();
  }
}

TEST(PbrtImageTextures, OnlyUsedTexturesAreCompiled) {
  const std::string path = image_dir() + "/unused.exr";
  write_exr(path, Image(2, 2), {}, {});
  TextureImages images{TextureSystemOptions{}};
  TextureGraph graph({imagemap(path, false), texture(TextureClass::Scale, false, {f(0.5f), f(2.0f)})}, "t.pbrt",
                     images);
  graph.use(1);
  EXPECT_EQ(graph.stats().defined, 2u);
  EXPECT_EQ(graph.stats().compiled, 1u);
  EXPECT_EQ(graph.stats().images, 0u);
  EXPECT_FALSE(images.built());
}

}  // namespace
}  // namespace kiln::test
