// The renderable world built from a SceneDesc: geometry for the accelerators, materials, lights and the per-shape
// data shading needs. Only what the scene uses is built (no sphere data without spheres, no light sampler without
// lights) and WorldStats records what was.
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lights/light.h"
#include "lights/light_sampler.h"
#include "materials/material.h"
#include "media/medium.h"
#include "renderer/accel/accelerator.h"
#include "renderer/world/features.h"
#include "renderer/world/material_mix.h"
#include "renderer/image_io/image_plugin.h"
#include "renderer/accel/geometry.h"
#include "scenes/scene.h"

namespace kiln {

class SceneTextures;
class AlphaCutouts;

struct ShapeData {
  int material = -1;
  int light = -1;            // index into World::lights when the shape emits
  bool smooth = false;
  int normals = -1;          // index into World::normals (per-vertex, same space as the mesh) or -1
  int uvs = -1;              // index into World::uvs (per-vertex texture coordinates) or -1
  int textures = -1;         // index into World::textures->bindings or -1 (no texture: shading reads no uv)
  MediumInterface media;     // the media on its two sides (indices into World::media)
};

struct WorldStats {
  size_t meshes = 0, triangles = 0, spheres = 0, instances = 0, quadrics = 0;
  size_t alpha_shapes = 0;   // shapes with an alpha cut-out (the accelerators test their opacity)
  size_t moving_shapes = 0;  // MotionBlur: shapes built as time-varying geometry
  size_t point_lights = 0, spot_lights = 0, directional_lights = 0, area_lights = 0, mesh_lights = 0,
         sphere_lights = 0, quadric_lights = 0, infinite_lights = 0, environment_maps = 0;
  size_t materials = 0;
  std::map<std::string, size_t> compiled_materials;  // Material::describe() -> how many materials compiled to it
  size_t interface_shapes = 0;  // shapes left out because their material only marks a boundary (pbrt "interface")
  size_t homogeneous_media = 0, grid_media = 0, rgb_grid_media = 0, nanovdb_media = 0, cloud_media = 0;
  size_t medium_boundaries = 0;    // shapes whose two sides hold different media
  size_t majorant_voxels = 0;      // over every heterogeneous medium's majorant grid
  size_t medium_grid_bytes = 0;    // lattices and NanoVDB grids
  std::vector<std::string> media;  // Medium describe(), in World::media order
  bool sphere_geometry_built = false;
  bool cone_sampler_built = false;  // sphere/ellipsoid lights present
  bool light_sampler_built = false;
  LightSamplerStats light_sampler;  // which sampler, its tree's size and build time
  double build_seconds = 0;
};

struct World {
  WorldGeometry geometry;
  std::vector<ShapeData> shape_data;            // parallel to geometry.shapes
  std::vector<std::vector<Vec3f>> normals;      // smooth per-vertex normals
  std::vector<std::vector<Vec2f>> uvs;          // per-vertex texture coordinates of textured meshes
  std::unique_ptr<SceneTextures> textures;      // only for scenes with textures (renderer/texture/scene_textures.h)
  std::unique_ptr<AlphaCutouts> alpha;          // only for scenes with alpha cut-outs (renderer/world/alpha_cutouts.h)
  std::vector<Material> materials;
  std::vector<MaterialMix> mixes;  // one per material for scenes with mix materials (kFeatureMix), else empty
  std::vector<Light> lights;
  std::vector<int> infinite_lights;  // indices into lights of what rays that leave the scene see
  // Participating media, built only when a shape bounds one or a camera sits in one (kFeatureMedia).
  std::vector<Medium> media;
  LightSampler light_sampler;
  Rgb ambient{0};
  Rgb background{0};
  uint32_t features = 0;
  float scene_radius = 1.0f;
  WorldStats stats;
  std::unique_ptr<Accelerator> accel;
  std::vector<std::string> unsupported;
  std::vector<std::string> warnings;  // found while building (e.g. degenerate lights left out)

  World();
  ~World();  // out of line: SceneTextures and AlphaCutouts are incomplete here
};

struct WorldOptions {
  AccelKind accel = AccelKind::Embree;
  // How next event estimation chooses lights (the rule set's, renderer/integrators/rules.h); absent: the scene's
  // default (lights/light_sampler.h default_light_sampler).
  std::optional<LightSamplerKind> light_sampler;
  bool build_accelerator = true;  // kiln info only needs the description and the feature mask
  EllipsoidPdf ellipsoid_pdf = EllipsoidPdf::Exact;  // the rule set's (renderer/integrators/rules.h)
  EnvMapSampling env_map_sampling = EnvMapSampling::ImportanceSampled;  // the rule set's (renderer/integrators/rules.h)
  TextureSystemOptions texture_system;  // OpenImageIO's cache, created only for scenes with image textures
};

// Throws kiln::Error on inconsistent descriptions (dangling material indices etc.).
std::unique_ptr<World> build_world(const SceneDesc& scene, const WorldOptions& options);
// Moves the arrays (positions, indices, normals, uvs) of every visible mesh that is not an instance base out of
// `scene` instead of copying them (a large mesh is then held once), then builds from the description as it is left;
// everything else in it (cameras, materials, lights, mesh names, instance bases) stays valid.
std::unique_ptr<World> build_world_taking_meshes(SceneDesc& scene, const WorldOptions& options);

}  // namespace kiln
