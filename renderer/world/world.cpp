#include "renderer/world/world.h"

#include <chrono>
#include <utility>

#include "core/error.h"
#include "renderer/image_io/image_io.h"
#include "renderer/texture/scene_textures.h"
#include "renderer/world/world_media.h"
#include "scenes/material_mapping.h"

namespace kiln {
namespace {

// One spare element of capacity lets Embree share the array instead of copying it (its SIMD loads may read
// past the last element).
template <typename T>
std::vector<T> with_spare_capacity(const std::vector<T>& v) {
  std::vector<T> out;
  out.reserve(v.size() + 1);
  out.assign(v.begin(), v.end());
  return out;
}

std::vector<Vec3f> transformed_points(const std::vector<Vec3f>& p, const Transform& t) {
  if (t.is_identity()) return with_spare_capacity(p);
  std::vector<Vec3f> out;
  out.reserve(p.size() + 1);
  for (const Vec3f& v : p) out.push_back(t.point(v));
  return out;
}

// The consuming build (build_world_taking_meshes) takes the description's arrays instead of copying them, so a large
// mesh is held once, not twice, while the accelerator is built and during the render (24 B/triangle).
template <typename T>
std::vector<T> take_with_spare_capacity(std::vector<T>& v) {
  std::vector<T> out = std::move(v);
  v = std::vector<T>();
  if (out.capacity() <= out.size()) out.reserve(out.size() + 1);
  return out;
}

std::vector<Vec3f> take_transformed_points(std::vector<Vec3f>& p, const Transform& t) {
  if (!t.is_identity())
    for (Vec3f& v : p) v = t.point(v);
  return take_with_spare_capacity(p);
}

// Area-weighted average of the adjacent face normals (the cross product's length is twice the area).
std::vector<Vec3f> vertex_normals(const TriangleMesh& m) {
  std::vector<Vec3f> n(m.p.size(), Vec3f(0.0f));
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const uint32_t a = m.idx[3 * t], b = m.idx[3 * t + 1], c = m.idx[3 * t + 2];
    const Vec3f fn = cross(m.p[b] - m.p[a], m.p[c] - m.p[a]);
    n[a] += fn;
    n[b] += fn;
    n[c] += fn;
  }
  for (Vec3f& v : n) {
    const float len = length(v);
    v = len > 0.0f ? v / len : Vec3f(0.0f);
  }
  return n;
}

// Emitters may come without a material (they only emit); everything else needs one.
void check_material(const SceneDesc& scene, int material, const std::string& name, bool emits) {
  if (material < 0 && emits) return;
  if (material < 0 || size_t(material) >= scene.materials.size())
    throw Error(scene.source_path, name, "has no valid material");
}

// The 2019 files spell the square light's radiance <Intensity>; a 2019 student renamed it Radiance and the 2021
// version of the same scene says Radiance, so both are read as radiance L (README, "Light conventions").
// The motion a shape gets. Lights are sampled where they are at time 0, so an emitter keeps still (with a warning)
// rather than be found by rays where its samples are not.
Vec3f shape_motion(World& w, const std::string& name, Vec3f motion, int light) {
  if (motion == Vec3f(0.0f)) return motion;
  if (light >= 0) {
    w.warnings.push_back(name + ": MotionBlur on an emitter is not rendered; it stays at its time-0 position");
    return Vec3f(0.0f);
  }
  w.features |= kFeatureMotionBlur;
  w.geometry.has_motion = true;
  ++w.stats.moving_shapes;
  return motion;
}

// EXR directly, other formats through the OpenImageIO plugin; a file that cannot be read names the scene element.
Image read_environment_map(const SceneDesc& scene, const EnvLightDesc& env) {
  try {
    Image img = read_image(env.image_path);
    if (img.width() <= 0 || img.height() <= 0) throw Error(env.image_path, "", "the image is empty");
    return img;
  } catch (const Error& e) {
    throw Error(scene.source_path, env.element, std::string("environment map: ") + e.what());
  }
}

AreaLight make_area_light(const AreaLightDesc& d) {
  if (d.edges) return AreaLight::parallelogram(d.position, (*d.edges)[0], (*d.edges)[1], d.radiance);
  return AreaLight::square(d.position, d.normal, d.size, d.radiance);
}

}  // namespace

World::World() = default;
World::~World() = default;

namespace {

// `consumable`, when given, is `scene` itself: its meshes' arrays are moved into the world (left empty).
std::unique_ptr<World> build_world_impl(const SceneDesc& scene, SceneDesc* consumable, const WorldOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  auto world = std::make_unique<World>();
  World& w = *world;
  w.background = scene.background;
  w.ambient = scene.ambient_light;
  w.unsupported = scene.unsupported;

  w.materials.reserve(scene.materials.size());
  for (const MaterialDesc& m : scene.materials) {
    w.materials.push_back(build_material(m, scene));
    const Material& built = w.materials.back();
    ++w.stats.compiled_materials[built.describe()];
    if (built.surface_flags() & kLobeGlossy) w.features |= kFeatureGlossy;
    if (built.has_delta()) w.features |= kFeatureDelta;
    if (built.oriented()) w.features |= kFeatureDielectric;
  }
  w.stats.materials = w.materials.size();
  if (!w.ambient.is_black()) w.features |= kFeatureAmbient;

  const bool media = scene_uses_media(scene);
  if (media) {
    build_world_media(scene, w);
    w.features |= kFeatureMedia;
  }
  // The media on a shape's sides; a transition only when the scene's media are built.
  const auto medium_interface = [&](const MediumInterfaceDesc& d, const std::string& name) {
    if (!media) return MediumInterface{};
    for (const int m : {d.inside, d.outside})
      if (m < -1 || m >= int(w.media.size())) throw Error(scene.source_path, name, "names a medium that does not exist");
    if (d.inside != d.outside) ++w.stats.medium_boundaries;
    return MediumInterface{d.inside, d.outside};
  };
  // Surfaces whose material only marks a boundary (pbrt's "interface") change no ray unless they bound a medium:
  // those are left out of the geometry, so they neither stop camera rays nor shadow lights.
  const auto invisible = [&](int material, const std::optional<Rgb>& emission, const MediumInterfaceDesc& sides) {
    const bool emits = emission && !emission->is_black();
    if (emits || material < 0 || size_t(material) >= w.materials.size() || !w.materials[size_t(material)].passes_through)
      return false;
    if (media && sides.inside != sides.outside) return false;
    ++w.stats.interface_shapes;
    return true;
  };

  // Textures: only for scenes that have them; their OpenImageIO TextureSystem only when one is an image.
  if (!scene.textures.empty()) {
    w.textures = std::make_unique<SceneTextures>(scene, options.texture_system);
    w.features |= kFeatureTextures;
  }
  const auto bind_textures = [&](const std::vector<int>& textures, int material, const Transform& to_world) {
    return w.textures && !textures.empty() ? w.textures->bind(scene, textures, material, to_world) : -1;
  };

  WorldGeometry& g = w.geometry;
  // Meshes: world-space copies for the scene, object-space prototypes for instanced bases.
  std::vector<int> prototype_of(scene.meshes.size(), -1);
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshDesc& m = scene.meshes[i];
    if (m.is_instance_base) {
      prototype_of[i] = int(g.prototypes.size());
      g.prototypes.push_back(TriangleMesh{with_spare_capacity(m.positions), with_spare_capacity(m.indices)});
    }
    if (!m.visible || m.indices.empty()) continue;
    check_material(scene, m.material, m.name, m.emission.has_value());
    if (invisible(m.material, m.emission, m.media)) continue;
    // Instance bases stay in the description: their prototype copy above was taken from it.
    MeshDesc* take = consumable && !m.is_instance_base ? &consumable->meshes[i] : nullptr;
    const bool has_uvs = !m.uvs.empty() && m.uvs.size() == m.positions.size();  // before `take` empties m
    TriangleMesh tm = take ? TriangleMesh{take_transformed_points(take->positions, m.to_world),
                                          take_with_spare_capacity(take->indices)}
                           : TriangleMesh{transformed_points(m.positions, m.to_world), with_spare_capacity(m.indices)};
    ShapeData sd;
    sd.material = m.material;
    sd.media = medium_interface(m.media, m.name);
    sd.smooth = m.smooth || !m.normals.empty();
    sd.textures = bind_textures(m.textures, m.material, m.to_world);
    if (sd.textures >= 0 && has_uvs) {
      sd.uvs = int(w.uvs.size());
      w.uvs.push_back(take ? std::exchange(take->uvs, {}) : m.uvs);
    }
    if (take) take->uvs = {};  // only textured shapes read texture coordinates
    if (!m.normals.empty()) {
      std::vector<Vec3f> n = take ? std::exchange(take->normals, {}) : m.normals;
      for (Vec3f& v : n) {
        const Vec3f wn = m.to_world.normal(v);
        const float len = length(wn);
        v = len > 0.0f ? wn / len : Vec3f(0.0f);
      }
      sd.normals = int(w.normals.size());
      w.normals.push_back(std::move(n));
    } else if (m.smooth) {
      sd.normals = int(w.normals.size());
      w.normals.push_back(vertex_normals(tm));
    }
    if (sd.smooth) w.features |= kFeatureSmoothNormals;
    if (m.emission && !m.emission->is_black()) {
      sd.light = int(w.lights.size());
      w.lights.emplace_back(MeshLight(tm.p, tm.idx, *m.emission, m.two_sided_emission));
      ++w.stats.mesh_lights;
      w.features |= kFeatureMeshLights;
    }
    w.stats.triangles += tm.triangle_count();
    ++w.stats.meshes;
    g.shapes.push_back(Shape{ShapeKind::Mesh, uint32_t(g.meshes.size()), shape_motion(w, m.name, m.motion, sd.light)});
    g.meshes.push_back(std::move(tm));
    w.shape_data.push_back(sd);
    w.features |= kFeatureTriangles;
  }
  for (const SphereDesc& s : scene.spheres) {
    check_material(scene, s.material, s.name, s.emission.has_value());
    if (invisible(s.material, s.emission, s.media)) continue;
    ShapeData sd;
    sd.material = s.material;
    sd.media = medium_interface(s.media, s.name);
    sd.textures = bind_textures(s.textures, s.material, s.to_world);
    const bool emits = s.emission && !s.emission->is_black();
    if (emits && !(s.radius > 0.0f)) {
      w.warnings.push_back(s.name + ": zero-radius light sphere emits nothing; left out of the lights");
    } else if (emits) {
      sd.light = int(w.lights.size());
      w.lights.emplace_back(SphereLight(s.center, s.radius, s.to_world, *s.emission, options.ellipsoid_pdf));
      ++w.stats.sphere_lights;
      w.features |= kFeatureSphereLights;
      w.stats.cone_sampler_built = true;
    }
    g.shapes.push_back(Shape{ShapeKind::Sphere, uint32_t(g.spheres.size()), shape_motion(w, s.name, s.motion, sd.light)});
    g.spheres.push_back(SphereShape{s.center, s.radius, s.to_world});
    w.shape_data.push_back(sd);
    w.features |= kFeatureSpheres;
  }
  w.stats.spheres = g.spheres.size();
  w.stats.sphere_geometry_built = !g.spheres.empty();
  // Object-space smooth normals for instanced prototypes, shared by all instances of one prototype.
  std::vector<int> prototype_normals(g.prototypes.size(), -2);
  std::vector<int> prototype_uvs(g.prototypes.size(), -1);
  for (const InstanceDesc& inst : scene.instances) {
    if (inst.base_mesh < 0 || size_t(inst.base_mesh) >= scene.meshes.size() || prototype_of[size_t(inst.base_mesh)] < 0)
      throw Error(scene.source_path, inst.name, "references a mesh that is not an instance base");
    const MeshDesc& base = scene.meshes[size_t(inst.base_mesh)];
    const int proto = prototype_of[size_t(inst.base_mesh)];
    ShapeData sd;
    sd.material = inst.material >= 0 ? inst.material : base.material;
    check_material(scene, sd.material, inst.name, false);
    if (invisible(sd.material, std::nullopt, inst.media)) continue;
    sd.media = medium_interface(inst.media, inst.name);
    sd.smooth = inst.smooth.value_or(base.smooth || !base.normals.empty());
    if (sd.smooth) {
      int& pn = prototype_normals[size_t(proto)];
      if (pn == -2) {
        pn = int(w.normals.size());
        w.normals.push_back(base.normals.empty() ? vertex_normals(g.prototypes[size_t(proto)]) : base.normals);
      }
      sd.normals = pn;
      w.features |= kFeatureSmoothNormals;
    }
    sd.textures = bind_textures(inst.textures, sd.material, inst.to_world);
    if (sd.textures >= 0 && !base.uvs.empty() && base.uvs.size() == base.positions.size()) {
      int& pu = prototype_uvs[size_t(proto)];
      if (pu == -1) {
        pu = int(w.uvs.size());
        w.uvs.push_back(base.uvs);
      }
      sd.uvs = pu;
    }
    g.shapes.push_back(Shape{ShapeKind::Instance, uint32_t(g.instances.size()), shape_motion(w, inst.name, inst.motion, -1)});
    g.instances.push_back(MeshInstance{uint32_t(proto), inst.to_world});
    w.shape_data.push_back(sd);
    w.stats.triangles += g.prototypes[size_t(proto)].triangle_count();
    w.features |= kFeatureInstances;
  }
  w.stats.instances = g.instances.size();

  const Bounds3f bounds = g.bounds();
  w.scene_radius = bounds.empty() ? 1.0f : std::max(0.5f * bounds.extent(), 1e-6f);

  for (const PointLightDesc& l : scene.point_lights) {
    w.lights.emplace_back(PointLight(l.position, l.intensity));
    ++w.stats.point_lights;
  }
  for (const SpotLightDesc& l : scene.spot_lights) {
    w.lights.emplace_back(SpotLight(l.position, l.direction, l.intensity, l.coverage_deg, l.falloff_deg,
                                    l.falloff == SpotFalloff::SmoothStep));
    ++w.stats.spot_lights;
  }
  for (const DirectionalLightDesc& l : scene.directional_lights) {
    w.lights.emplace_back(DirectionalLight(l.direction, l.radiance, w.scene_radius));
    ++w.stats.directional_lights;
  }
  if (w.stats.point_lights + w.stats.spot_lights + w.stats.directional_lights > 0) w.features |= kFeaturePointLights;
  for (const AreaLightDesc& l : scene.area_lights) {
    w.lights.emplace_back(make_area_light(l));
    ++w.stats.area_lights;
    w.features |= kFeatureAreaLights;
  }
  for (const InfiniteLightDesc& l : scene.infinite_lights) {
    w.infinite_lights.push_back(int(w.lights.size()));
    w.lights.emplace_back(InfiniteLight(l.radiance, w.scene_radius));
    ++w.stats.infinite_lights;
    w.features |= kFeatureInfiniteLights;
  }
  for (const EnvLightDesc& l : scene.env_lights) {
    w.infinite_lights.push_back(int(w.lights.size()));
    w.lights.emplace_back(ImageInfiniteLight(read_environment_map(scene, l), w.scene_radius, options.env_map_sampling));
    ++w.stats.environment_maps;
    w.features |= kFeatureInfiniteLights | kFeatureEnvironmentMap;
  }
  if (!w.lights.empty()) {
    w.light_selector = LightSelector(w.lights, options.light_selection);
    w.stats.light_selector_built = true;
  }
  for (const CameraDesc& c : scene.cameras)
    if (c.aperture_size > 0.0f) w.features |= kFeatureDepthOfField;

  if (options.build_accelerator) w.accel = make_accelerator(options.accel, g);
  w.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return world;
}

}  // namespace

std::unique_ptr<World> build_world(const SceneDesc& scene, const WorldOptions& options) {
  return build_world_impl(scene, nullptr, options);
}

std::unique_ptr<World> build_world_taking_meshes(SceneDesc& scene, const WorldOptions& options) {
  return build_world_impl(scene, &scene, options);
}

}  // namespace kiln
