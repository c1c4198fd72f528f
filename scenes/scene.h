// Format-independent scene description. Loaders (XML, JSON, PLY, OBJ) only fill this; the renderer builds its
// world (geometry, materials, lights) from it. Plain data, no behaviour.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/transform.h"

namespace kiln {

struct TonemapDesc {
  std::string tmo = "Photographic";
  float key = 0.18f;        // TMOOptions[0]
  float burn_percent = 0;   // TMOOptions[1]
  float saturation = 1.0f;
  float gamma = 2.2f;       // ignored when srgb
  bool srgb = false;        // Gamma "sRGB" or 2018 GammaCorrection sRGB
};

enum class RendererKind { RayTracing, PathTracing };

struct PathTracingFlags {
  bool importance_sampling = false;
  bool next_event_estimation = false;
  bool russian_roulette = false;
};

struct CameraDesc {
  std::string id;
  Vec3f position{0, 0, 0};
  Vec3f gaze{0, 0, -1};  // GazePoint already converted to a direction
  Vec3f up{0, 1, 0};
  bool use_fov = false;  // lookAt / simple: FovY; otherwise near_plane
  float fov_y_deg = 45.0f;
  std::array<float, 4> near_plane{-1, 1, -1, 1};  // l r b t
  float near_distance = 1.0f;
  int width = 0, height = 0;
  int num_samples = 1;
  std::string image_name;  // file name only (ImageName)
  float focus_distance = 0.0f;
  float aperture_size = 0.0f;  // 0: pinhole
  bool left_handed = false;
  std::optional<TonemapDesc> tonemap;
  RendererKind renderer = RendererKind::RayTracing;
  bool renderer_explicit = false;  // the scene named a renderer (else Kiln's default applies)
  PathTracingFlags pt;
};

enum class BrdfKind { OriginalPhong, ModifiedPhong, OriginalBlinnPhong, ModifiedBlinnPhong, TorranceSparrow, Lambert };

struct BrdfDesc {
  int id = 0;
  BrdfKind kind = BrdfKind::ModifiedBlinnPhong;
  float exponent = 1.0f;
  bool normalized = false;
  bool kd_fresnel = false;                 // TorranceSparrow kdfresnel
  std::optional<float> refractive_index;   // 2019 TorranceSparrow child RefractiveIndex
};

enum class MaterialType { Plain, Mirror, Dielectric, Conductor };

struct MaterialDesc {
  int id = 0;
  std::optional<int> brdf;  // index into SceneDesc::brdfs (not the XML id)
  MaterialType type = MaterialType::Plain;
  Rgb ambient{0}, diffuse{0}, specular{0}, mirror{0};
  float phong_exponent = 1.0f;
  float roughness = 0.0f;
  Rgb transparency{0};          // 2019 dielectric marker / per-unit transmittance
  float refraction_index = 1.0f;
  Rgb absorption_coefficient{0};  // 2021 dielectric Beer-Lambert
  float absorption_index = 0.0f;  // conductor kappa
  bool degamma = false;
  bool has_refraction_index = false;
};

// Triangle mesh in object space. Indices are 0-based triplets into positions.
// Each Loop subdivision level multiplies the triangle count by 4; 7 levels of the 8 K killeroo are 136 M triangles.
inline constexpr int kMaxSubdivisionLevels = 7;

struct MeshDesc {
  std::string name;     // for messages, e.g. "Mesh id=3"
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;
  std::vector<Vec3f> normals;  // per vertex, empty when absent
  std::vector<Vec2f> uvs;      // per vertex, empty when absent
  bool smooth = false;         // shadingMode smooth: average face normals per vertex when normals are absent
  int material = -1;           // index into SceneDesc::materials
  Transform to_world;
  std::optional<Rgb> emission;  // LightMesh radiance (front side)
  bool is_instance_base = false;  // referenced by a MeshInstance (kept in object space for instancing)
  bool visible = true;            // false: only a prototype for instances, not itself in the scene
  int subdivide = 0;              // Loop subdivision levels requested for this mesh
};

struct SphereDesc {
  std::string name;
  Vec3f center{0, 0, 0};
  float radius = 1.0f;
  Transform to_world;  // applied after centring: world = to_world * translate(center) * scale(radius)
  int material = -1;
  std::optional<Rgb> emission;  // LightSphere radiance
};

struct InstanceDesc {
  std::string name;
  int base_mesh = -1;     // index into SceneDesc::meshes
  Transform to_world;     // full object->world (resetTransform already resolved)
  int material = -1;
  std::optional<bool> smooth;
};

struct PointLightDesc { Vec3f position; Rgb intensity; };
struct DirectionalLightDesc { Vec3f direction; Rgb radiance; };
struct SpotLightDesc { Vec3f position; Vec3f direction; Rgb intensity; float coverage_deg = 0; float falloff_deg = 0; };
// Square (Normal + Size) or parallelogram (edge vectors) emitter; radiance constant.
struct AreaLightDesc {
  Vec3f position, normal;
  float size = 1.0f;
  std::optional<std::array<Vec3f, 2>> edges;  // 2018 EdgeVector1/2 form
  Rgb radiance;
  bool radiance_is_intensity = false;  // 2019 <Intensity> spelling (see README for the convention)
};
struct EnvLightDesc { std::string image_path; };

struct SceneDesc {
  std::string source_path;  // file it was loaded from
  std::string format;       // "ceng795-xml", "cs171-json", "ply", "obj"
  Rgb background{0};
  std::optional<float> shadow_ray_epsilon;
  std::optional<float> intersection_test_epsilon;
  std::optional<int> max_recursion_depth;
  std::vector<CameraDesc> cameras;
  std::vector<BrdfDesc> brdfs;
  std::vector<MaterialDesc> materials;
  std::vector<MeshDesc> meshes;
  std::vector<SphereDesc> spheres;
  std::vector<InstanceDesc> instances;
  Rgb ambient_light{0};
  std::vector<PointLightDesc> point_lights;
  std::vector<DirectionalLightDesc> directional_lights;
  std::vector<SpotLightDesc> spot_lights;
  std::vector<AreaLightDesc> area_lights;
  std::vector<EnvLightDesc> env_lights;
  bool png_gamma_encode = false;  // CS171: the PNG preview applies gamma 2.2 (no tonemap)
  // Features present in the file that the renderer does not render yet (e.g. "textures", "motion blur");
  // reported by `kiln info` and warned about once at render time.
  std::vector<std::string> unsupported;
  std::vector<std::string> warnings;
};

}  // namespace kiln
