// The textures of one scene, compiled for shading (CENG795 spec §8; README "Textures"). Built only for scenes with
// course textures or with a rendered pbrt-v4 material that needs per-hit evaluation; the OpenImageIO TextureSystem
// (through the plugin, renderer/image_io/image_plugin.h) only when one of the textures used is an image.
//
// pbrt-v4 materials whose parameters are textured, or that carry a displacement or normal map, are bound to the
// shapes that use them and resolved at each hit (renderer/texture/textured_material.h) from the scene's texture graph
// (renderer/texture/texture_graph.h); only the textures such a material reads are compiled.
//
// Per hit, a shape's binding says what its textures do: replace or blend k_d, replace k_s, replace the whole
// shading (replace_all), bump (height (R+G+B)/3 of an image, or Perlin noise) or replace the shading normal
// (normal map, tangent space from dp/du, dp/dv). Materials are shared between shapes, so a textured hit shades with
// a copy of its material's texturable prototype that carries the texel's k_d / k_s (no allocation: Material is a
// value type).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/transform.h"
#include "materials/material.h"
#include "renderer/image_io/image_plugin.h"
#include "renderer/texture/footprint.h"
#include "renderer/texture/image_textures.h"
#include "renderer/texture/texture_graph.h"
#include "renderer/texture/textured_material.h"
#include "scenes/scene.h"

namespace kiln {

struct CompiledTexture {
  TextureSource source = TextureSource::Image;
  DecalMode decal = DecalMode::ReplaceKd;
  bool bump = false;
  float bump_factor = 1.0f;
  bool degamma = false;
  // Image
  void* handle = nullptr;
  TextureQuery query;          // interp and wrap; s, t filled per lookup
  float value_scale = 1.0f;    // format_max / Normalizer: OpenImageIO's [0, 1] back to the file's values, normalised
  bool grey = false;
  int width = 1, height = 1;
  // Perlin
  NoiseConversion noise = NoiseConversion::Linear;
  float noise_scale = 1.0f;
  // Checkerboard
  float checker_scale = 1.0f, checker_offset = 0.0f;
  Rgb black{0.0f}, white{1.0f};
  float normalizer = 1.0f;     // procedural textures: colours are divided by it
};

// What the textures of one shape do; -1: nothing of that kind. A later texture of the same kind wins.
struct TextureBinding {
  int kd = -1, ks = -1, all = -1, normal = -1, bump = -1;
  bool blend_kd = false;
  bool footprint = false;  // the kd, ks or all texture is filtered over the hit's footprint (trilinear / ewa)
  int material = -1;  // index into SceneTextures::materials (the texturable prototype) or -1: no k_d / k_s texture
  int pbrt_material = -1;  // index into SceneTextures::pbrt_materials: a pbrt-v4 material resolved per hit
  // A mix with a textured amount or a component resolved per hit: the hit finishes the mix's choice (the textured
  // amounts' values there) and looks up the component it chose (pbrt_material_of).
  bool pbrt_mix = false;
  // Procedural textures are evaluated in the object's own space (the course's: veach-ajar's floor, scaled 1.8x along
  // x by its transformation, has squares 1.8x wider along x in its reference).
  Transform to_object;
};

// A material whose k_d / k_s a texture sets: built once with placeholder reflectances so that no lobe a texture
// needs is left out, then copied per hit.
struct TexturableMaterial {
  Material prototype;
  Rgb kd{0.0f}, ks{0.0f};      // the material's own (linear) values: blend_kd mixes the texel with kd
  float lambert_scale = 1.0f;  // a Lambert surface's reflectance per unit k_d (pi for the course's un-normalised forms)
};

struct TextureBuildStats {
  size_t textures = 0, images = 0, procedural = 0, bindings = 0;
  size_t filtered = 0;            // images filtered over a footprint (Interpolation trilinear / ewa)
  size_t footprint_bindings = 0;  // bindings that compute a hit's footprint (a filtered k_d / k_s / replace_all)
  bool texture_system_built = false;
  float cache_limit_mb = 0.0f;
  TextureGraphStats pbrt;         // pbrt-v4 textures: defined, compiled (used by a rendered material), images
  size_t textured_materials = 0;  // pbrt-v4 materials resolved per hit
};


class SceneTextures {
 public:
  // Throws kiln::Error naming the scene file and the Texture element when an image is missing or unreadable.
  SceneTextures(const SceneDesc& scene, const TextureSystemOptions& options);
  ~SceneTextures();
  SceneTextures(const SceneTextures&) = delete;
  SceneTextures& operator=(const SceneTextures&) = delete;

  // A binding for a shape with these textures (indices into SceneDesc::textures) and material; -1 when they do nothing
  // to a surface (e.g. only a background texture) and the material needs no per-hit evaluation. A pbrt-v4 material's
  // textures are compiled here (their images opened: may throw kiln::Error naming the texture).
  int bind(const SceneDesc& scene, const std::vector<int>& textures, int material, const Transform& to_world);

  // Texture value at a hit (colour, normalised, degamma applied); p in the object's own space. Filtered images
  // (trilinear / ewa) average over the footprint fp; a zero footprint reads the finest level (bilinear).
  Rgb value(const CompiledTexture& t, Vec2f uv, Vec3f p, const UvFootprint& fp = {}) const;
  Rgb value(int texture, Vec2f uv, Vec3f p, const UvFootprint& fp = {}) const {
    return value(textures_[size_t(texture)], uv, p, fp);
  }
  // The shading normal bumped by height texture t (n unit, in ng's hemisphere; dpdu/dpdv the surface's derivatives).
  Vec3f bumped_normal(const CompiledTexture& t, Vec3f n, Vec2f uv, Vec3f p, Vec3f dpdu, Vec3f dpdv) const;
  // The normal a tangent-space normal map gives.
  Vec3f mapped_normal(const CompiledTexture& t, Vec3f n, Vec2f uv, Vec3f p, Vec3f dpdu) const;

  const std::vector<CompiledTexture>& textures() const { return textures_; }
  const std::vector<TextureBinding>& bindings() const { return bindings_; }
  const std::vector<TexturableMaterial>& materials() const { return materials_; }
  const std::vector<TexturedPbrtMaterial>& pbrt_materials() const { return pbrt_materials_; }
  const TextureGraph& graph() const { return graph_; }
  // The pbrt_materials index of SceneDesc material m, or -1 when it is not resolved per hit.
  int pbrt_material_of(size_t m) const { return m < pbrt_material_of_desc_.size() ? pbrt_material_of_desc_[m] : -1; }
  // Compiles pbrt-v4 texture i for a lookup outside materials (a shape's alpha); may throw as bind() does.
  void use_pbrt_texture(int i) { graph_.use(i); }
  int background() const { return background_; }
  // What a camera ray that misses every surface sees at film position `film` (the pixel centre in [0, 1]^2, x to the
  // right, y down; renderer/integrators/integrator.h): the replace_background texture there, Normalizer and degamma applied as
  // for every texture. A procedural one is evaluated at the point (u, v, 0) of the image plane.
  Rgb background_value(Vec2f film) const { return value(background_, film, Vec3f(film.x, film.y, 0.0f)); }
  TextureBuildStats stats() const;
  TextureCacheStats cache_stats() const { return images_.cache_stats(); }

 private:
  Rgb image_value(const CompiledTexture& t, Vec2f uv, const UvFootprint& fp) const;
  float height(const CompiledTexture& t, Vec2f uv, Vec3f p) const;

  std::vector<CompiledTexture> textures_;
  std::vector<TextureBinding> bindings_;
  std::vector<TexturableMaterial> materials_;
  std::vector<int> material_of_desc_;  // SceneDesc material -> materials_ index (built on first use)
  std::vector<TexturedPbrtMaterial> pbrt_materials_;
  int use_pbrt_material(const SceneDesc& scene, int material);
  std::vector<int> pbrt_material_of_desc_;  // SceneDesc material -> pbrt_materials_ index (made on first use)
  int background_ = -1;
  // A member declared before everything that opens images, so that a constructor which throws after the texture
  // system exists still frees it.
  TextureImages images_;
  TextureGraph graph_;
  TextureBuildStats stats_;
};

// Whether a shape with this material (an index into SceneDesc::materials) needs the scene's textures although it has
// no course textures: a pbrt-v4 material evaluated per hit, or a mix with such a component or a textured amount.
bool material_needs_textures(const SceneDesc& scene, int material);

}  // namespace kiln
