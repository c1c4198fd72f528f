// Object creation for the pbrt-v4 loader. As in pbrt-v4, reading the file (scenes/pbrt/parser.cpp: tokens,
// directives, blocks, transforms, the graphics state) is kept apart from making the scene's objects out of a
// directive's parameter list: materials (scenes/pbrt/materials.cpp), textures (scenes/pbrt/textures.cpp) and lights
// (scenes/pbrt/lights.cpp), each written into the SceneDesc. Shapes and cameras are made by scenes/pbrt/shapes.h and
// scenes/pbrt/camera.h. Everything a builder cannot render is reported through PbrtDiagnostics.
#pragma once
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
  // NamedMaterial: the material's index. pbrt-v4 looks names up once the whole file is read, so a name may be used
  // before its MakeNamedMaterial (the collection's contemporary-bathroom does): it gets a slot now, which the
  // definition fills.
  int use_named_material(const std::string& name, const std::string& file, int line);
  // At the end of the scene: a name used but defined nowhere is an error naming where it was used; with
  // allow_missing_files (its definition may be in a missing file) pbrt's default material stands in, reported.
  void finish_named_materials();
  // pbrt's default material (diffuse, reflectance 0.5), made on first use; `file` names the scene in messages.
  int default_material(const std::string& file);

  // Textures (scenes/pbrt/textures.cpp).
  void make_texture(const std::string& name, const std::string& type, const std::string& cls, const PbrtParams& ps);

  // Lights (scenes/pbrt/lights.cpp). light_to_world: the transform in effect at the directive.
  void make_light(const std::string& type, const PbrtParams& ps, const Transform& light_to_world);
  // AreaLightSource: what the shapes that follow emit; empty for area lights Kiln does not render (warned).
  std::optional<PbrtAreaLight> make_area_light(const std::string& type, const PbrtParams& ps);

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
  struct ForwardMaterial {
    int slot = -1;
    std::string file;  // where the name was first used
    int line = 0;
  };
  std::map<std::string, ForwardMaterial> forward_materials_;  // used, not defined yet
  void fill_material_slot(int slot, int made);
  std::map<std::string, PbrtTextureDef> textures_;
  int default_material_ = -1;
};

}  // namespace kiln
