// Texture graphs in the scene description (pbrt-v4's texture language: scenes/pbrt/textures.cpp fills them,
// renderer/texture/texture_graph.h evaluates them). A texture is a node whose operands are constants or other
// textures; material parameters that take a texture are TexturedFloat / TexturedRgb. Plain data, no behaviour.
//
// Classes (pbrt-v4's file-format documentation), with the operand slots each reads:
//   constant       value                        operand 0
//   scale          tex * scale                  operands 0 (tex), 1 (scale, float)
//   mix            (1 - amount) tex1 + amount tex2           operands 0, 1, 2 (amount, float)
//   directionmix   |n . dir| tex1 + (1 - |n . dir|) tex2      operands 0, 1; `direction`
//   checkerboard   tex1 on even cells, tex2 on odd (2-D on the mapping, 3-D on the texture-space point)
//                                               operands 0, 1; `dimension`
//   dots           one value in a dot, another elsewhere     operands 0 (dot), 1 (background)
//   bilerp         bilinear in (s, t) between v00, v01, v10, v11   operands 0..3
//   imagemap       an image file (`image`)
//   fbm, wrinkled  fractional Brownian motion / turbulence of Perlin noise (float)   `octaves`, `roughness`
//   windy          |fbm(p / 10)| * fbm(p) (float)
//   marble         a colour spline of sin(y + variation fbm) (spectrum)   `octaves`, `roughness`, `scale`, `variation`
#pragma once
#include <array>
#include <string>

#include "core/color.h"
#include "core/transform.h"

namespace kiln {

// A material parameter or texture operand: the constant `value`, or, when texture >= 0, the value of texture
// SceneDesc::pbrt_textures[texture] at the hit. A plain value converts to an untextured parameter.
struct TexturedFloat {
  float value = 0.0f;
  int texture = -1;
  TexturedFloat() = default;
  TexturedFloat(float v, int tex = -1) : value(v), texture(tex) {}  // NOLINT: implicit from a constant
  bool textured() const { return texture >= 0; }
  bool operator==(const TexturedFloat&) const = default;
};
struct TexturedRgb {
  Rgb value{0.0f};
  int texture = -1;
  TexturedRgb() = default;
  TexturedRgb(Rgb v, int tex = -1) : value(v), texture(tex) {}  // NOLINT: implicit from a constant
  bool textured() const { return texture >= 0; }
  bool operator==(const TexturedRgb&) const = default;
};

enum class TextureClass { Constant, Scale, Mix, DirectionMix, Checkerboard, Dots, Bilerp, ImageMap, Fbm, Wrinkled,
                          Windy, Marble };

// How a hit becomes texture coordinates (s, t) for the 2-D classes:
//   uv           s = uscale u + udelta, t = vscale v + vdelta
//   spherical    (theta / pi, phi / 2 pi) of the texture-space point's direction from the origin (theta from +z)
//   cylindrical  ((pi + atan2(y, x)) / 2 pi, z) of the texture-space point
//   planar       (udelta + p . v1, vdelta + p . v2) of the texture-space point
// The 3-D classes (3-D checkerboard, fbm, wrinkled, windy, marble) read the texture-space point itself.
enum class TextureMapping { Uv, Spherical, Cylindrical, Planar };
struct TextureMappingDesc {
  TextureMapping kind = TextureMapping::Uv;
  float su = 1.0f, sv = 1.0f, du = 0.0f, dv = 0.0f;  // uscale, vscale, udelta, vdelta (planar: du, dv only)
  Vec3f v1{1, 0, 0}, v2{0, 1, 0};                    // planar axes
  Transform world_to_texture;                        // the inverse of the transform at the Texture directive
};

// What an image lookup does outside [0, 1]^2: repeat, black, clamp to the edge, or fold across the edges of an
// octahedral sphere map (a point past an edge continues on the mirrored side).
enum class ImageWrap { Repeat, Black, Clamp, OctahedralSphere };
// How an 8- or 16-bit file's values become linear: as they are, the sRGB curve, or v^gamma. Float files are linear.
enum class ImageEncoding { Linear, Srgb, Gamma };
// point: the nearest texel, bilinear: bilinear within one MIP level, trilinear: between two levels, ewa:
// anisotropic along the footprint (the level chosen from the hit's footprint).
enum class ImageFilter { Point, Bilinear, Trilinear, Ewa };

struct ImageTextureDesc {
  std::string path;  // resolved against the scene file; also in SceneDesc::external_files
  ImageFilter filter = ImageFilter::Bilinear;
  ImageWrap wrap = ImageWrap::Repeat;
  ImageEncoding encoding = ImageEncoding::Linear;
  float gamma = 2.2f;  // ImageEncoding::Gamma
  float scale = 1.0f;  // texel values are multiplied by it (before invert)
  bool invert = false; // max(0, 1 - value)
};

// Operand slots (TextureDesc::operands).
inline constexpr int kTexOperandTex1 = 0, kTexOperandTex2 = 1, kTexOperandAmount = 2;  // mix, directionmix, checkerboard
inline constexpr int kTexOperandTex = 0, kTexOperandScale = 1;                          // scale
inline constexpr int kTexOperandDot = 0, kTexOperandBackground = 1;                     // dots
inline constexpr int kTexOperandV00 = 0, kTexOperandV01 = 1, kTexOperandV10 = 2, kTexOperandV11 = 3;  // bilerp

struct PbrtTextureDesc {
  std::string name;  // for messages and statistics: `Texture "grid"` with the file and line
  TextureClass cls = TextureClass::Constant;
  bool is_float = false;  // a float texture (one value) or a spectrum texture (RGB)
  TextureMappingDesc mapping;
  // Constants or textures; a float operand's constant is value.r (== g == b). Float operands of a spectrum texture
  // (scale, amount) name float textures.
  std::array<TexturedRgb, 4> operands;
  Vec3f direction{0, 1, 0};  // directionmix, world space, unit
  int dimension = 2;         // checkerboard
  int octaves = 8;           // fbm, wrinkled, marble
  float roughness = 0.5f;    // fbm, wrinkled, marble: the amplitude ratio between octaves
  float marble_scale = 1.0f, variation = 0.2f;  // marble
  ImageTextureDesc image;    // imagemap
};

}  // namespace kiln
