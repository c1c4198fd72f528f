// pbrt-v4 texture graphs (scenes/texture_graph.h) compiled for evaluation at hits. A texture is compiled, and its
// image opened, the first time something rendered uses it (use()), with everything it reads: a texture that only an
// unrendered material names costs nothing.
//
// Definitions (pbrt-v4's textures.h/.cpp and its file-format documentation):
//   * imagemap: the image at (s, 1 - t) (image rows run down, t up), filtered over the footprint as `filter` says,
//     wrapped as `wrap` says, 8- and 16-bit files decoded (sRGB, gamma) before filtering; value = scale * texel,
//     then max(0, 1 - value) when inverted (spectrum textures are clamped at 0 either way). A float texture reads
//     a one-channel image's value, a three-channel image's channel average, a four-channel image's alpha (its
//     average when the alpha is 1 everywhere).
//   * scale: tex * scale (0 without evaluating tex when scale is 0); mix: (1 - amount) tex1 + amount tex2;
//     directionmix: a tex1 + (1 - a) tex2 with a = |n . dir|; either operand is skipped when its weight is 0.
//   * checkerboard: tex1 on cells whose integer parts of (s, t) (or of the point, 3-D) add up even, tex2 on odd;
//     the weight of tex2 is the checker averaged over a triangle filter 1.5 footprints wide, so it blurs across
//     edges no finer than a pixel.
//   * dots: one dot of radius 0.35 in each cell around an integer (s, t) where the noise there is positive, shifted
//     by noise; the dot's value in it, the background's elsewhere (the loader says which parameter is which).
//   * bilerp: (1-s)(1-t) v00 + s(1-t) v10 + (1-s)t v01 + st v11.
//   * fbm, wrinkled (turbulence), windy, marble: renderer/texture/fractal_noise.h on the texture-space point.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/color.h"
#include "renderer/texture/image_textures.h"
#include "renderer/texture/texture_mapping.h"
#include "scenes/texture_graph.h"

namespace kiln {

struct TextureGraphStats {
  size_t defined = 0;   // Texture directives in the scene
  size_t compiled = 0;  // compiled because something rendered uses them
  size_t images = 0;    // of them imagemaps (each an opened file)
};

class TextureGraph {
 public:
  // scene_file names the scene in messages; images is where imagemaps are opened (it outlives the graph).
  TextureGraph(const std::vector<PbrtTextureDesc>& textures, const std::string& scene_file, TextureImages& images);

  // Compiles texture i and the textures it reads (opens their images; throws kiln::Error naming the texture's
  // file and line when one cannot be read).
  void use(int i);
  // Whether compiled texture i (or one it reads) looks at the footprint (filtered images, checkerboards, noise).
  bool needs_footprint(int i) const { return nodes_[size_t(i)].needs_footprint; }

  // Values at the hit; i must have been compiled.
  float eval_float(int i, const TextureEvalContext& c) const;
  Rgb eval_rgb(int i, const TextureEvalContext& c) const;

  const TextureGraphStats& stats() const { return stats_; }

 private:
  struct CompiledImage {
    void* handle = nullptr;
    TextureQuery query;  // interp and wrap; the rest per lookup
    int channels = 3;
    bool opaque_alpha = false;  // a four-channel image whose alpha is 1 everywhere
  };
  struct Node {
    PbrtTextureDesc desc;
    CompiledImage image;
    bool compiled = false, needs_footprint = false;
  };

  template <typename T>
  T eval(int i, const TextureEvalContext& c) const;
  template <typename T>
  T operand(const TexturedRgb& o, const TextureEvalContext& c) const;
  template <typename T>
  T image_value(const Node& n, const TextureEvalContext& c) const;
  template <typename T>
  T noise_value(const Node& n, const TextureEvalContext& c) const;
  void open_image(Node& n);

  std::vector<Node> nodes_;
  std::string scene_file_;
  TextureImages& images_;
  TextureGraphStats stats_;
};

}  // namespace kiln
