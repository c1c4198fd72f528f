// Object creation for the pbrt-v4 loader. As in pbrt-v4, reading the file (scenes/pbrt/parser.cpp: tokens,
// directives, blocks, transforms, the graphics state) is kept apart from making the scene's objects out of a
// directive's parameter list: materials (scenes/pbrt/materials.cpp), textures (scenes/pbrt/textures.cpp), lights
// (scenes/pbrt/lights.cpp) and media (scenes/pbrt/media.cpp), each written into the SceneDesc. Shapes and cameras
// are made by scenes/pbrt/shapes.h and scenes/pbrt/camera.h. Everything a builder cannot render is reported through
// PbrtDiagnostics.
#pragma once
#include <functional>
#include <map>
#include <optional>
#include <string>

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

// Turns a file name written in the scene into a path (throws kiln::Error naming `line` when it cannot be found).
using PbrtResolve = std::function<std::string(const std::string& name, int line)>;

// An AreaLightSource in effect: the shapes that follow emit it.
struct PbrtAreaLight {
  Rgb radiance;
  bool two_sided = false;
};

// A named texture (Texture directive).
struct PbrtTextureDef {
  bool is_float = false;
  std::string cls;
  std::optional<float> value;  // constant float texture
  std::optional<Rgb> rgb;      // constant spectrum texture
};

class PbrtBuilder {
 public:
  explicit PbrtBuilder(SceneDesc& scene) : scene_(scene), diag_(scene) {}
  PbrtBuilder(const PbrtBuilder&) = delete;
  PbrtBuilder& operator=(const PbrtBuilder&) = delete;

  SceneDesc& scene() { return scene_; }
  PbrtDiagnostics& diagnostics() { return diag_; }

  // Materials (scenes/pbrt/materials.cpp): an index into SceneDesc::materials.
  int make_material(const std::string& type, const PbrtParams& ps);
  // MakeNamedMaterial: ps holds "type" and the material's parameters.
  void make_named_material(const std::string& name, const PbrtParams& ps);
  std::optional<int> named_material(const std::string& name) const;
  // pbrt's default material (diffuse, reflectance 0.5), made on first use; `file` names the scene in messages.
  int default_material(const std::string& file);

  // Textures (scenes/pbrt/textures.cpp).
  void make_texture(const std::string& name, const std::string& type, const std::string& cls, const PbrtParams& ps);

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
  // Material parameters that may name a texture: constant textures are read, others warned (the default is used).
  float float_param(const PbrtParams& ps, const std::string& name, float def);
  Rgb spectrum_param(const PbrtParams& ps, const std::string& name, SpectrumUse use, Rgb def);
  const PbrtTextureDef& texture_def(const PbrtParams& ps, const std::string& name) const;
  void texture_not_rendered(const PbrtParams& ps, const std::string& param, const std::string& tex,
                            const PbrtTextureDef& t);
  void read_roughness(const PbrtParams& ps, PbrtMaterialDesc& pm);
  float interface_eta(const PbrtParams& ps);

  Rgb light_spectrum(const PbrtParams& ps, const std::string& name);
  void infinite_light(const PbrtParams& ps, float scale);

  SceneDesc& scene_;
  PbrtDiagnostics diag_;
  std::map<std::string, int> named_materials_;
  std::map<std::string, int> named_media_;
  std::map<std::string, PbrtTextureDef> textures_;
  int default_material_ = -1;
};

}  // namespace kiln
