// Format-independent scene description. Loaders (XML, JSON, PLY, OBJ, pbrt-v4) only fill this; the renderer builds its
// world (geometry, materials, lights) from it. Plain data, no behaviour.
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/color.h"
#include "core/quadric.h"
#include "core/transform.h"
#include "scenes/texture_graph.h"

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

// Whose rules render the scene by default (README, "Two rule sets"): Kiln's own (MIS, unbiased roulette, exact
// pdfs) or the conventions of a course's reference renderer, which reproduce that course's reference images. The
// loader that knows the file sets it; `--rules` overrides it; nothing else decides it.
enum class SceneRules { Kiln, Ceng795Course, Cs171Course };

// Pixel reconstruction filter, sampled by filter importance sampling (pbrt-v4): the pixel's samples are drawn
// with density proportional to |filter| and weighted by its sign, so no sample is shared between pixels.
enum class PixelFilterKind { Box, Triangle, Gaussian, BlackmanHarris, Mitchell };
struct PixelFilterDesc {
  PixelFilterKind kind = PixelFilterKind::Box;
  float radius = 0.5f;        // pixels, in x and y
  float sigma = 0.5f;         // Gaussian standard deviation (pixels)
  float b = 1.0f / 3.0f, c = 1.0f / 3.0f;  // Mitchell-Netravali B, C
};

struct PathTracingFlags {
  bool importance_sampling = false;
  bool next_event_estimation = false;
  bool russian_roulette = false;
};

// How a camera maps the film to rays (pbrt-v4's camera types; CENG795 and CS171 cameras are Perspective). Camera
// space has x along the image's right, y along its up and z forward (-gaze).
enum class CameraProjection { Perspective, Orthographic, Spherical, Realistic };
// A spherical camera's film: pbrt's equal-area square (Clarberg's octahedral mapping) or latitude-longitude.
enum class SphericalMapping { EqualArea, Equirectangular };

// One interface of a realistic camera's lens system, in metres, listed from the scene side to the film side as
// pbrt's lens files list them: curvature radius (0: the aperture stop), thickness to the next interface, index of
// refraction behind it (0 reads as air), aperture radius.
struct LensInterfaceDesc {
  float curvature_radius = 0, thickness = 0, eta = 0, aperture_radius = 0;
};
struct LensSystemDesc {
  std::string file;                          // the lens file
  std::string directive;                     // where the camera is written, for messages (file: line (directive))
  std::vector<LensInterfaceDesc> interfaces;  // the stop's aperture radius is already the requested aperture's
  float focus_distance = 10.0f;               // metres, to the plane in focus
  float film_diagonal = 0.035f;               // metres (pbrt Film "diagonal", in mm in the file)
};

// A transform that moves over the shutter: `end` at end_time, the description's own transform at start_time, pbrt's
// interpolation between them (core/animated_transform.h). Times are fractions of the shutter interval (0 when it
// opens, 1 when it closes) and may lie outside it.
struct TransformMotionDesc {
  Transform end;
  float start_time = 0.0f, end_time = 1.0f;
};

// Where a moving camera is at the end of its motion (CameraDesc::motion); times as in TransformMotionDesc.
struct CameraMotionDesc {
  Vec3f position{0, 0, 0}, gaze{0, 0, -1}, up{0, 1, 0};
  float start_time = 0.0f, end_time = 1.0f;
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
  bool disk_lens = false;      // aperture_size is the diameter of a disk lens (pbrt lensradius) instead of a square's side
  bool left_handed = false;
  std::optional<TonemapDesc> tonemap;
  bool srgb_without_tonemap = false;  // 2018 GammaCorrection sRGB without a Tonemap: the LDR preview is sRGB-encoded
  RendererKind renderer = RendererKind::RayTracing;
  bool renderer_explicit = false;  // the scene named a renderer (else Kiln's default applies)
  PathTracingFlags pt;
  std::optional<PixelFilterDesc> filter;  // the scene's pixel filter (pbrt PixelFilter); else the rules' default
  CameraProjection projection = CameraProjection::Perspective;
  // Orthographic: near_plane is the screen window in camera-space units (no NearDistance, rays along the gaze).
  SphericalMapping spherical_mapping = SphericalMapping::EqualArea;
  std::optional<LensSystemDesc> lens;  // Realistic
  // The film the image is cut from when it is cropped (pbrt cropwindow): its full size and the crop's corner.
  // Spherical and realistic cameras map the whole film; the perspective ones fold the crop into near_plane.
  int full_width = 0, full_height = 0;  // 0: width, height
  int crop_x = 0, crop_y = 0;
  // Write Kiln's AOV layers with the image (pbrt Film "gbuffer") unless the command line names its own.
  bool aov_layers = false;
  // Every sample's radiance is multiplied by this (pbrt's imaging ratio: Film "iso" / 100 times the exposure time).
  float film_scale = 1.0f;
  // pbrt's Film "maxcomponentvalue": a sample whose largest channel (after film_scale) is above it is scaled down to
  // it, its hue kept. Infinity: samples are kept as they are.
  float max_component = std::numeric_limits<float>::infinity();
  // The camera moves over the shutter: (position, gaze, up) hold at the start time, `motion` at the end time.
  std::optional<CameraMotionDesc> motion;
  int medium = -1;  // index into SceneDesc::media of the medium the camera sits in; -1: vacuum
};

// Participating media (pbrt-v4 MakeNamedMedium; scenes/pbrt/media.cpp reads them, renderer/world builds them into
// media/). Coefficients are per unit length of world space with the file's "scale" applied, spectra reduced to RGB.
struct HomogeneousMediumDesc {
  Rgb sigma_a{1.0f}, sigma_s{1.0f};
  Rgb le{0.0f};  // emitted radiance (Le x Lescale)
};
// A lattice of nx x ny x nz samples (x fastest) over the box [p0, p1] of the medium's space.
struct MediumLattice {
  int nx = 1, ny = 1, nz = 1;
  Vec3f p0{0.0f}, p1{1.0f};
  size_t count() const { return size_t(nx) * size_t(ny) * size_t(nz); }
};
struct GridMediumDesc {  // "uniformgrid"
  MediumLattice lattice;
  std::vector<float> density;
  Rgb sigma_a{1.0f}, sigma_s{1.0f};
  Rgb le{0.0f};
  std::vector<float> le_scale;     // lattice.count() values, or one (pbrt-v4's 1x1x1 lattice)
  std::vector<float> temperature;  // empty, or lattice.count() values: blackbody emission instead of le
  float temperature_offset = 0.0f, temperature_scale = 1.0f;
};
struct RgbGridMediumDesc {  // "rgbgrid"; an absent lattice is empty (1 everywhere for sigma_a, sigma_s)
  MediumLattice lattice;
  std::vector<Rgb> sigma_a, sigma_s, le;
  float scale = 1.0f, le_scale = 1.0f;
};
struct NanoVdbMediumDesc {  // "nanovdb"
  std::string path;  // resolved
  std::string density_grid = "density", temperature_grid = "temperature";
  Rgb sigma_a{1.0f}, sigma_s{1.0f};
  float le_scale = 1.0f, temperature_offset = 0.0f, temperature_scale = 1.0f;
};
struct CloudMediumDesc {  // "cloud" (media/cloud_medium.h)
  Vec3f p0{0.0f}, p1{1.0f};
  Rgb sigma_a{1.0f}, sigma_s{1.0f};
  float density = 1.0f, wispiness = 1.0f, frequency = 5.0f;
};
struct MediumDesc {
  std::string name;     // as the scene names it
  std::string element;  // where it is defined, for messages about it (e.g. `line 12 (MakeNamedMedium "fog")`)
  Transform to_world;   // the medium's own space (lattices and NanoVDB grids live in it)
  float g = 0.0f;       // Henyey-Greenstein asymmetry
  std::variant<HomogeneousMediumDesc, GridMediumDesc, RgbGridMediumDesc, NanoVdbMediumDesc, CloudMediumDesc> params;
  // Radiance of a blackbody at the temperatures of media/emission_table.h, for media with a temperature grid.
  std::vector<Rgb> blackbody;
};
// The media on the two sides of a shape: indices into SceneDesc::media, -1 for none (vacuum). "inside" is the side
// the shape's normal points away from (meshes: the winding's normal; spheres: the centre).
struct MediumInterfaceDesc {
  int inside = -1, outside = -1;
  bool operator==(const MediumInterfaceDesc&) const = default;
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

// pbrt-v4 materials (scenes/pbrt/materials.cpp fills this, scenes/material_mapping builds it). Spectral parameters are
// already reduced to linear RGB by the loader. A parameter pbrt lets a texture set is a TexturedFloat / TexturedRgb:
// untextured, its value is the parameter; textured, the material is built again at every hit from the textures'
// values there (renderer/texture/textured_material.h).
enum class PbrtMaterialKind {
  Diffuse,
  Conductor,
  Dielectric,
  CoatedDiffuse,
  CoatedConductor,
  DiffuseTransmission,
  ThinDielectric,
  Interface
};
struct PbrtMaterialDesc {
  PbrtMaterialKind kind = PbrtMaterialKind::Diffuse;
  TexturedRgb reflectance{Rgb(0.5f)};        // diffuse, coateddiffuse, diffusetransmission
  TexturedRgb transmittance{Rgb(0.25f)};     // diffusetransmission
  float scale = 1.0f;                        // diffusetransmission: multiplies reflectance and transmittance
  bool conductor_by_reflectance = false;     // (coated) conductor given by "reflectance" (conductor_reflectance)
  TexturedRgb conductor_reflectance{Rgb(1.0f)};
  TexturedRgb conductor_eta{Rgb(0.2f, 0.92f, 1.1f)};  // (coated) conductor complex IOR (pbrt's default is copper)
  TexturedRgb conductor_k{Rgb(3.91f, 2.45f, 2.14f)};
  TexturedFloat eta{1.5f};  // dielectric / thindielectric IOR, coateddiffuse / coatedconductor interface IOR
  TexturedFloat uroughness{0.0f}, vroughness{0.0f};  // as written in the file ("roughness" sets both);
                                                     // coatedconductor: the interface's
  TexturedFloat conductor_uroughness{0.0f}, conductor_vroughness{0.0f};  // coatedconductor: the conductor's
  bool remap_roughness = true;
  TexturedFloat thickness{0.01f};  // coated layers
  TexturedRgb albedo{Rgb(0.0f)};   // coated layers' medium albedo
  TexturedFloat g{0.0f};           // coated layers' Henyey-Greenstein asymmetry
  int max_depth = 10;              // coated layers' random-walk length
  int n_samples = 1;               // coated layers' estimator samples
  int displacement = -1;  // float texture (SceneDesc::pbrt_textures): bump mapping by its height along the normal
  int normal_map = -1;    // image texture (SceneDesc::pbrt_textures): a tangent-space normal map
};

// A material that is one of two others at each hit (pbrt-v4 "mix"): the second with probability `amount`, chosen
// by a hash of the hit so that the image is the blend in expectation. `amount` may be a float texture, evaluated at
// the hit before the choice. Components may be mixes themselves (no cycles: the loader rejects them).
struct MaterialMixDesc {
  std::array<int, 2> materials{-1, -1};  // indices into SceneDesc::materials
  TexturedFloat amount{0.5f};            // a constant, or a float texture (SceneDesc::pbrt_textures)
};

// Calls f on every parameter of d (a PbrtMaterialDesc, const or not) that a texture may set (TexturedFloat /
// TexturedRgb): what the per-hit evaluation fills in. A new texturable parameter must be listed here.
template <typename Desc, typename F>
void for_each_texturable(Desc& d, F&& f) {
  f(d.reflectance);
  f(d.transmittance);
  f(d.conductor_reflectance);
  f(d.conductor_eta);
  f(d.conductor_k);
  f(d.eta);
  f(d.uroughness);
  f(d.vroughness);
  f(d.conductor_uroughness);
  f(d.conductor_vroughness);
  f(d.thickness);
  f(d.albedo);
  f(d.g);
}

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
  std::optional<PbrtMaterialDesc> pbrt;  // set by the pbrt-v4 loader; the fields above are then unused
  std::optional<MaterialMixDesc> mix;    // a per-hit choice between two materials; every other field is unused
};

// Triangle mesh in object space. Indices are 0-based triplets into positions.
// Each Loop subdivision level multiplies the triangle count by 4; 7 levels of the 8 K killeroo are 136 M triangles.
inline constexpr int kMaxSubdivisionLevels = 7;

// Textures (CENG795 spec §8; README "Textures"). Image textures are read through OpenImageIO's TextureSystem;
// Perlin noise and the checkerboard are evaluated at the hit point in the object's own space.
enum class TextureSource { Image, Perlin, Checkerboard };
// What a texture does to the surface it is attached to.
enum class DecalMode { ReplaceKd, BlendKd, ReplaceKs, ReplaceAll, ReplaceNormal, BumpNormal, ReplaceBackground };
// Nearest / Bilinear read the finest level (the course's). Trilinear and Ewa are Kiln's own: filtered over the hit's
// pixel footprint (renderer/texture/footprint.h), isotropic across two MIP levels or anisotropic along it.
enum class TextureFilter { Nearest, Bilinear, Trilinear, Ewa };
enum class TextureWrap { Repeat, Clamp };
// Perlin noise n in [-1, 1] to a value: Linear (patch) (n + 1) / 2, AbsVal (vein) |n|.
enum class NoiseConversion { Linear, AbsVal };

struct TextureDesc {
  std::string name;            // for messages, e.g. "Texture id=3" or "TextureMap id=2"
  TextureSource source = TextureSource::Image;
  std::string image_path;      // resolved against the scene file's folder (Image only)
  TextureFilter filter = TextureFilter::Bilinear;
  TextureWrap wrap = TextureWrap::Repeat;
  DecalMode decal = DecalMode::ReplaceKd;
  std::optional<float> normalizer;  // texel values are divided by it; absent: the image format's maximum (255 for 8 bit)
  bool degamma = false;        // texel^2.2 after normalising
  bool bump = false;           // also a height field that perturbs the shading normal (2019 bumpmap="true", bump_normal)
  float bump_factor = 1.0f;    // bumpmapMultiplier / BumpFactor
  NoiseConversion noise = NoiseConversion::Linear;
  float noise_scale = 1.0f;    // Perlin: the point is multiplied by it (ScalingFactor / NoiseScale)
  float checker_scale = 1.0f, checker_offset = 0.0f;  // Scale (ScalingFactor), Offset
  Rgb black{0.0f}, white{1.0f};                        // BlackColor, WhiteColor
};

// pbrt's "alpha" on a shape: its opacity, the constant `value` or, when texture >= 0, the float texture
// SceneDesc::pbrt_textures[texture] at the hit (renderer/world/alpha_cutouts.h; any class and mapping, as material
// parameters read them). Opacity 1 everywhere (the default) is no cut-out at all.
struct ShapeAlphaDesc {
  float value = 1.0f;
  int texture = -1;
  bool cuts() const { return texture >= 0 || value < 1.0f; }
};

// An area light whose radiance is an image over the shape's (u, v) (pbrt-v4's "diffuse" area light with "filename"):
// radiance = the shape's `emission` (pbrt's "scale", grey) x the image at (u, 1 - v) (lights/emission_image.h).
struct EmissionImageDesc {
  std::string path;     // resolved; also in SceneDesc::external_files
  std::string element;  // where the scene asks for it (e.g. "line 12 (AreaLightSource ...)"), for messages
};

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
  bool two_sided_emission = false;  // emission leaves both sides (pbrt "twosided" area lights)
  std::optional<EmissionImageDesc> emission_image;  // radiance = emission x this image at the hit's (u, v)
  bool is_instance_base = false;  // referenced by a MeshInstance (kept in object space for instancing)
  bool visible = true;            // false: only a prototype for instances, not itself in the scene
  int subdivide = 0;              // Loop subdivision levels requested for this mesh
  Vec3f motion{0, 0, 0};          // MotionBlur: world-space translation over the shutter interval (at time t: t * motion)
  std::vector<int> textures;      // indices into SceneDesc::textures
  MediumInterfaceDesc media;
  ShapeAlphaDesc alpha;           // pbrt "alpha" (also for the instances of an instance base)
};

struct SphereDesc {
  std::string name;
  Vec3f center{0, 0, 0};
  float radius = 1.0f;
  Transform to_world;  // applied after centring: world = to_world * translate(center) * scale(radius)
  int material = -1;
  std::optional<Rgb> emission;  // LightSphere radiance
  Vec3f motion{0, 0, 0};        // MotionBlur (see MeshDesc::motion)
  std::optional<TransformMotionDesc> to_world_motion;  // to_world moves over the shutter (pbrt ActiveTransform)
  std::vector<int> textures;    // indices into SceneDesc::textures
  MediumInterfaceDesc media;
  ShapeAlphaDesc alpha;         // pbrt "alpha": the sphere is then built as a quadric (pbrt's (u, v))
};

// A pbrt-v4 disk, cylinder or partial sphere (core/quadric.h), placed by to_world. flip: its normal is the opposite
// of the natural one (pbrt's ReverseOrientation exclusive-or a mirroring to_world), which makes the other side the
// one that emits (one-sided emission) and the outside of a dielectric.
struct QuadricDesc {
  std::string name;
  Quadric quadric;
  Transform to_world;
  bool flip = false;
  int material = -1;
  std::optional<Rgb> emission;
  bool two_sided_emission = false;
  std::optional<EmissionImageDesc> emission_image;  // radiance = emission x this image at pbrt's (u, v)
  Vec3f motion{0, 0, 0};  // MotionBlur (see MeshDesc::motion)
  std::optional<TransformMotionDesc> to_world_motion;  // to_world moves over the shutter (pbrt ActiveTransform)
  ShapeAlphaDesc alpha;
  MediumInterfaceDesc media;
};

// A sphere as a whole-turn quadric sphere, where pbrt's (u, v) are needed (an alpha texture, an emission image).
inline QuadricDesc quadric_of_sphere(const SphereDesc& s) {
  QuadricDesc q;
  q.name = s.name;
  q.quadric = *make_quadric(QuadricType::Sphere, s.radius, 0.0f, 0.0f, -s.radius, s.radius, 360.0f).quadric;
  q.to_world = s.to_world * Transform::translate(s.center);
  q.material = s.material;
  q.emission = s.emission;
  q.motion = s.motion;
  if (s.to_world_motion) {
    q.to_world_motion = s.to_world_motion;
    q.to_world_motion->end = s.to_world_motion->end * Transform::translate(s.center);
  }
  q.alpha = s.alpha;
  q.media = s.media;
  return q;
}

struct InstanceDesc {
  std::string name;
  int base_mesh = -1;     // index into SceneDesc::meshes
  Transform to_world;     // full object->world (resetTransform already resolved)
  int material = -1;
  std::optional<bool> smooth;
  Vec3f motion{0, 0, 0};  // MotionBlur (see MeshDesc::motion)
  std::optional<TransformMotionDesc> to_world_motion;  // to_world moves over the shutter (pbrt ActiveTransform)
  std::vector<int> textures;  // indices into SceneDesc::textures; empty: the base mesh's
  MediumInterfaceDesc media;
};

struct PointLightDesc { Vec3f position; Rgb intensity; };
struct DirectionalLightDesc { Vec3f direction; Rgb radiance; };
// How a spot light fades between its falloff and coverage cones: the course's s^4 with s linear in cos, or pbrt's
// smoothstep in cos.
enum class SpotFalloff { Quartic, SmoothStep };
struct SpotLightDesc {
  Vec3f position; Vec3f direction; Rgb intensity; float coverage_deg = 0; float falloff_deg = 0;
  SpotFalloff falloff = SpotFalloff::Quartic;
};
// Square (Normal + Size) or parallelogram (edge vectors) emitter; radiance constant.
struct AreaLightDesc {
  Vec3f position, normal;
  float size = 1.0f;
  std::optional<std::array<Vec3f, 2>> edges;  // 2018 EdgeVector1/2 form
  Rgb radiance;
  bool radiance_is_intensity = false;  // 2019 <Intensity> spelling (see README for the convention)
};
// An HDR image on an infinitely distant sphere (CENG795 SphericalDirectionalLight, pbrt-v4 "infinite" with
// "filename"); `element` names the scene element (with its file and line) for messages about the image.
//   LatLongYUp  the course's lat-long map (y up; lights/image_infinite_light.h)
//   LatLongZUp  pbrt-v3's lat-long map: z up, u = phi / 2 pi with phi from +x towards +y, v = theta / pi
//   EqualArea   pbrt-v4's octahedral equal-area square (z up)
enum class EnvMapFormat { LatLongYUp, LatLongZUp, EqualArea };
struct EnvLightDesc {
  std::string image_path;
  std::string element;
  EnvMapFormat format = EnvMapFormat::LatLongYUp;
  // EqualArea only: a non-square image (which pbrt-v4 refuses) with a 2:1 aspect is read as LatLongZUp, with a
  // warning; any other non-square image is an error.
  bool lat_long_if_not_square = false;
  Transform light_to_world;  // the map's frame in the world (its linear part)
  float scale = 1.0f;        // radiance = texel x scale
  // pbrt's "illuminance" E: the scale is further multiplied by E / k, k the illuminance the map gives a surface
  // facing the map's +z, computed as pbrt-v4 computes it (renderer/world/environment_map.h).
  std::optional<float> illuminance;
};
// Constant radiance arriving from every direction (pbrt "infinite" light with "L"), seen by rays that escape.
struct InfiniteLightDesc { Rgb radiance; };

// What a loader made of one directive of the file (pbrt), for `kiln info`: rendered as written, rendered with a
// stand-in (a default material, a different filter, the start of a motion), or left out (a shape, a light, a
// parameter). Remarks change nothing in the image (a deprecated spelling, a replaced sampler).
enum class LoadOutcome { Rendered, Substituted, Ignored, Remark };
struct LoadNote {
  std::string file;
  int line = 0;               // of the note (an unused parameter's own line)
  std::string directive;      // e.g. Shape "disk", MakeNamedMaterial "floor"
  std::string kind;           // the key of SceneDesc::directives it counts under: Shape "disk", MakeNamedMaterial
  int directive_line = 0;     // where the directive starts (one directive may have several notes)
  LoadOutcome outcome = LoadOutcome::Remark;
  std::string feature;    // Substituted / Ignored: what is not rendered as written (as listed in SceneDesc::unsupported)
  std::string message;
};
// How many directives of one kind (e.g. Shape "trianglemesh") the file has, and where the first one is.
struct DirectiveCount {
  size_t count = 0;
  std::string first_file;
  int first_line = 0;
};

struct SceneDesc {
  std::string source_path;  // file it was loaded from
  std::string format;       // "ceng795-xml", "cs171-json", "ply", "obj": for messages only, never for decisions
  SceneRules rules = SceneRules::Kiln;
  Rgb background{0};
  std::optional<float> shadow_ray_epsilon;
  std::optional<float> intersection_test_epsilon;
  std::optional<int> max_recursion_depth;
  std::vector<CameraDesc> cameras;
  std::vector<BrdfDesc> brdfs;
  std::vector<MaterialDesc> materials;
  std::vector<MeshDesc> meshes;
  std::vector<SphereDesc> spheres;
  std::vector<QuadricDesc> quadrics;
  std::vector<InstanceDesc> instances;
  Rgb ambient_light{0};
  std::vector<PointLightDesc> point_lights;
  std::vector<DirectionalLightDesc> directional_lights;
  std::vector<SpotLightDesc> spot_lights;
  std::vector<AreaLightDesc> area_lights;
  std::vector<EnvLightDesc> env_lights;
  std::vector<InfiniteLightDesc> infinite_lights;
  std::vector<MediumDesc> media;
  // Whether triangles facing away from camera rays are skipped (CENG795 BackfaceCulling); unset: the rule set's
  // default (README, "Course conventions").
  std::optional<bool> backface_culling;
  std::vector<TextureDesc> textures;
  std::vector<PbrtTextureDesc> pbrt_textures;  // pbrt-v4 texture graphs (scenes/texture_graph.h), read only when used
  std::optional<int> background_texture;  // index into textures: what camera rays that miss see (replace_background)
  bool png_gamma_encode = false;  // CS171: the PNG preview applies gamma 2.2 (no tonemap)
  // Files the render reads that the loader does not read itself (texture images, environment maps, volume grids):
  // the scene's identity (renderer/render/scene_fingerprint.h) covers them as well as the files read through
  // read_file_bytes (scenes/parse_util.h). Absolute or relative to the working directory, as the loader resolved them.
  std::vector<std::string> external_files;
  // Features present in the file that the renderer does not render yet (e.g. "textures", "motion blur");
  // reported by `kiln info` and warned about once at render time.
  std::vector<std::string> unsupported;
  std::vector<std::string> warnings;
  // pbrt: every directive by kind, and a note for each one not rendered as written (and each remark), in file
  // order. A directive without a Substituted or Ignored note is rendered as written.
  std::map<std::string, DirectiveCount> directives;
  std::vector<LoadNote> notes;
};

}  // namespace kiln
