// Object creation for the pbrt-v4 loader. As in pbrt-v4, reading the file (scenes/pbrt/parser.cpp: tokens,
// directives, blocks, transforms, the graphics state) is kept apart from making the scene's objects out of a
// directive's parameter list: materials (scenes/pbrt/materials.cpp), textures (scenes/pbrt/textures.cpp), lights
// (scenes/pbrt/lights.cpp) and media (scenes/pbrt/media.cpp), each written into the SceneDesc. Shapes and cameras
// are made by scenes/pbrt/shapes.h and scenes/pbrt/camera.h. Everything a builder cannot render is reported through
// PbrtDiagnostics.
#pragma once
#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/transform.h"
#include "scenes/pbrt/diagnostics.h"
#include "scenes/pbrt/params.h"
#include "scenes/scene.h"

namespace kiln {

// pbrt-v4's defaults.
inline constexpr float kPbrtDefaultReflectance = 0.5f;  // "diffuse" reflectance, also pbrt's default material
inline constexpr float kPbrtDefaultDielectricEta = 1.5f;
inline constexpr float kPbrtDefaultSpotConeAngle = 30.0f, kPbrtDefaultSpotConeDelta = 5.0f;
inline constexpr float kPbrtDefaultCoatThickness = 0.01f;
inline constexpr int kPbrtDefaultCoatMaxDepth = 10;
// Noise textures sum this many octaves at most (each is a Perlin evaluation at a frequency 1.99x the last, so more
// would only cost time).
inline constexpr int kPbrtMaxNoiseOctaves = 32;
inline constexpr float kPbrtDefaultDiffuseTransmission = 0.25f;  // both "reflectance" and "transmittance"
inline constexpr float kPbrtDefaultMixAmount = 0.5f;

// Turns a file name written in the scene into a path (throws kiln::Error naming `line` when it cannot be found).
using PbrtResolve = std::function<std::string(const std::string& name, int line)>;

// An AreaLightSource in effect: the shapes that follow emit it.
struct PbrtAreaLight {
  Rgb radiance;  // with an image: its multiplier (pbrt's "scale")
  bool two_sided = false;
  std::optional<EmissionImageDesc> image;  // pbrt's "filename"
};

// A named texture (Texture directive): float and spectrum textures have separate names, as in pbrt-v4.
struct PbrtTextureKey {
  std::string name;
  bool is_float = false;
  auto operator<=>(const PbrtTextureKey&) const = default;
};
struct PbrtTextureDef {
  int index = -1;   // into SceneDesc::pbrt_textures; -1: a class Kiln does not render (warned), e.g. ptex
  std::string cls;  // the class as written, for messages
};

// A file named in the scene, resolved as Include resolves it (a missing file throws, naming the file and line).
using PbrtResolver = std::function<std::string(const std::string& name, const PbrtParams& ps)>;

class PbrtBuilder {
 public:
  PbrtBuilder(SceneDesc& scene, PbrtResolver resolve) : scene_(scene), diag_(scene), resolve_(std::move(resolve)) {}
  PbrtBuilder(const PbrtBuilder&) = delete;
  PbrtBuilder& operator=(const PbrtBuilder&) = delete;

  SceneDesc& scene() { return scene_; }
  PbrtDiagnostics& diagnostics() { return diag_; }

  // Materials (scenes/pbrt/materials.cpp): an index into SceneDesc::materials.
  int make_material(const std::string& type, const PbrtParams& ps);
  // MakeNamedMaterial: ps holds "type" and the material's parameters.
  void make_named_material(const std::string& name, const PbrtParams& ps);
  std::optional<int> named_material(const std::string& name) const;
  // NamedMaterial: the material's index. pbrt-v4 looks names up once the whole file is read, so a name may be used
  // before its MakeNamedMaterial (the collection's contemporary-bathroom does): it gets a slot now, which the
  // definition fills.
  int use_named_material(const std::string& name, const std::string& file, int line);
  // At the end of the scene: a name used but defined nowhere is an error naming where it was used; with
  // allow_missing_files (its definition may be in a missing file) pbrt's default material stands in, reported.
  void finish_named_materials();
  // pbrt's default material (diffuse, reflectance 0.5), made on first use; `file` names the scene in messages.
  int default_material(const std::string& file);
  // Once the whole scene is read: the names of "mix" materials' components (error: a missing one, or mixes that
  // contain each other, at the mix's line).
  void resolve_mixes();

  // Textures (scenes/pbrt/textures.cpp). to_world: the transform in effect at the directive.
  void make_texture(const std::string& name, const std::string& type, const std::string& cls, const PbrtParams& ps,
                    const Transform& to_world);

  // A shape's "alpha" (scenes/pbrt/alpha.cpp): a float, or any float texture (SceneDesc::pbrt_textures). A missing
  // texture or a spectrum texture throws.
  ShapeAlphaDesc shape_alpha(const PbrtParams& ps);

  // Lights (scenes/pbrt/lights.cpp). light_to_world: the transform in effect at the directive.
  void make_light(const std::string& type, const PbrtParams& ps, const Transform& light_to_world);
  // AreaLightSource: what the shapes that follow emit; empty for area lights Kiln does not render (warned).
  std::optional<PbrtAreaLight> make_area_light(const std::string& type, const PbrtParams& ps);

  // Media (scenes/pbrt/media.cpp): MakeNamedMedium into SceneDesc::media. medium_to_world: the transform in effect.
  void make_medium(const std::string& name, const PbrtParams& ps, const Transform& medium_to_world,
                   const PbrtResolve& resolve);
  // The index into SceneDesc::media of a named medium; -1 for a medium Kiln leaves empty; none when undefined.
  std::optional<int> named_medium(const std::string& name) const;

 private:
  // Parameters that may name a texture (materials and texture operands): a constant, a constant texture's value, or
  // the texture. A texture of a class Kiln does not render is warned and the default used.
  TexturedFloat float_param(const PbrtParams& ps, const std::string& name, float def);
  TexturedRgb spectrum_param(const PbrtParams& ps, const std::string& name, SpectrumUse use, Rgb def);
  // The texture `tex` that parameter `param` names, of the kind the parameter needs; -1 when its class is not
  // rendered (warned). A missing texture, or one of the other kind, throws naming the file and line.
  int texture_ref(const PbrtParams& ps, const std::string& param, const std::string& tex, bool is_float);
  void read_mapping(const PbrtParams& ps, const Transform& to_world, TextureMappingDesc& m);
  void read_image_texture(const PbrtParams& ps, ImageTextureDesc& image);
  int add_image_texture(const std::string& name, const ImageTextureDesc& image, bool is_float);
  void add_external_file(const std::string& path);  // once, however many textures read it
  void read_operands(const PbrtParams& ps, PbrtTextureDesc& t);
  // "<prefix>roughness", "<prefix>uroughness", "<prefix>vroughness".
  void read_roughness(const PbrtParams& ps, const std::string& prefix, TexturedFloat& u, TexturedFloat& v);
  TexturedFloat interface_eta(const PbrtParams& ps, const std::string& name);
  void read_conductor(const PbrtParams& ps, const std::string& prefix, PbrtMaterialDesc& pm);
  void read_layers(const PbrtParams& ps, PbrtMaterialDesc& pm);
  void read_mix(const PbrtParams& ps, MaterialDesc& d);
  std::vector<int> mix_cycle_from(int material) const;
  std::string material_name(int material) const;
  void read_bump(const PbrtParams& ps, PbrtMaterialDesc& pm);

  Rgb light_spectrum(const PbrtParams& ps, const std::string& name);
  void infinite_light(const PbrtParams& ps, float scale, const Transform& light_to_world);
  void image_infinite_light(const PbrtParams& ps, const std::string& file, float scale,
                            const Transform& light_to_world);

  SceneDesc& scene_;
  PbrtDiagnostics diag_;
  PbrtResolver resolve_;
  std::map<std::string, int> named_materials_;
  struct ForwardMaterial {
    int slot = -1;
    std::string file;  // where the name was first used
    int line = 0;
  };
  std::map<std::string, ForwardMaterial> forward_materials_;  // used, not defined yet
  void fill_material_slot(int slot, int made);
  std::map<std::string, int> named_media_;
  // A mix whose component names are resolved at the end (they may be defined after it).
  struct PendingMix {
    int material;
    std::array<std::string, 2> names;
    std::string file, context;
    int line;
    std::string where() const { return "line " + std::to_string(line) + " (" + context + ")"; }
  };
  std::vector<PendingMix> pending_mixes_;
  std::map<PbrtTextureKey, PbrtTextureDef> textures_;
  int default_material_ = -1;
};

}  // namespace kiln
