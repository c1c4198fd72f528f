#include "renderer/world/world.h"

#include <chrono>
#include <optional>
#include <utility>

#include "core/error.h"
#include "renderer/world/alpha_cutouts.h"
#include "renderer/world/emission_images.h"
#include "renderer/world/environment_map.h"
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

// The animated transform of a sphere, quadric or instance whose to_world moves (pbrt ActiveTransform), as an index into
// WorldGeometry::motions; -1 when it does not move. Emitters stay at their start, as with shape_motion.
int32_t shape_animation(World& w, const std::string& name, const Transform& start,
                        const std::optional<TransformMotionDesc>& motion, int light) {
  if (!motion) return -1;
  if (light >= 0) {
    w.warnings.push_back(name + ": a moving emitter is not rendered moving; it stays at its start transform");
    return -1;
  }
  AnimatedTransform a;
  try {
    a = AnimatedTransform(start, motion->start_time, motion->end, motion->end_time);
  } catch (const Error& e) {
    throw Error(name + ": its motion cannot be interpolated: " + e.what());
  }
  if (!a.animated()) return -1;
  w.features |= kFeatureMotionBlur;
  w.geometry.has_motion = true;
  ++w.stats.moving_shapes;
  w.geometry.motions.push_back(a);
  return int32_t(w.geometry.motions.size() - 1);
}

AreaLight make_area_light(const AreaLightDesc& d) {
  if (d.edges) return AreaLight::parallelogram(d.position, (*d.edges)[0], (*d.edges)[1], d.radiance);
  return AreaLight::square(d.position, d.normal, d.size, d.radiance);
}

}  // namespace

World::World() = default;
World::~World() = default;

namespace {

// The arrays of a mesh that the world keeps, moved out of the description by build_world_taking_meshes.
struct MeshArrays {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;
  std::vector<Vec3f> normals;
  std::vector<Vec2f> uvs;
};

// Builds a World from a description it only reads; the arrays of meshes in `taken` (by mesh index; empty: copy them
// all) are moved into the world instead of copied.
class WorldBuilder {
 public:
  WorldBuilder(const SceneDesc& scene, const WorldOptions& options, std::vector<std::optional<MeshArrays>>* taken)
      : scene_(scene), options_(options), taken_(taken), world_(std::make_unique<World>()), w_(*world_) {}

  std::unique_ptr<World> build() {
    const auto start = std::chrono::steady_clock::now();
    w_.background = scene_.background;
    w_.ambient = scene_.ambient_light;
    w_.unsupported = scene_.unsupported;
    if (!w_.ambient.is_black()) w_.features |= kFeatureAmbient;
    add_materials();
    add_textures();
    add_media();
    add_meshes();
    add_spheres();
    add_quadrics();
    add_instances();
    add_alpha_test();
    const Bounds3f bounds = w_.geometry.bounds();
    w_.scene_radius = bounds.empty() ? 1.0f : std::max(0.5f * bounds.extent(), 1e-6f);
    add_lights();
    for (const CameraDesc& c : scene_.cameras) {
      if (c.aperture_size > 0.0f || c.projection == CameraProjection::Realistic) w_.features |= kFeatureDepthOfField;
      if (c.motion) w_.features |= kFeatureMotionBlur;  // rays carry a time for the camera's pose
    }
    if (options_.build_accelerator) w_.accel = make_accelerator(options_.accel, w_.geometry);
    w_.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(world_);
  }

 private:
  void add_materials() {
    w_.materials.reserve(scene_.materials.size());
    for (const MaterialDesc& m : scene_.materials) {
      w_.materials.push_back(build_material(m, scene_));
      if (m.mix) {  // shades as its components, which are materials of their own
        ++w_.stats.compiled_materials["mix"];
        continue;
      }
      ++w_.stats.compiled_materials[w_.materials.back().describe()];
      note_features(w_.materials.back());
      if (m.pbrt && needs_per_hit_evaluation(*m.pbrt))  // what its textures may make of it at a hit
        for (const Material& v : per_hit_variants(*m.pbrt)) note_features(v);
    }
    w_.stats.materials = w_.materials.size();
    w_.mixes = build_material_mixes(scene_);
    if (!w_.mixes.empty()) w_.features |= kFeatureMix;
  }

  void note_features(const Material& built) {
    if (built.surface_flags() & kLobeGlossy) w_.features |= kFeatureGlossy;
    if (built.has_delta()) w_.features |= kFeatureDelta;
    if (built.oriented()) w_.features |= kFeatureDielectric;
  }

  // Textures: only for scenes with course textures or a rendered shape whose pbrt material is resolved per hit;
  // their OpenImageIO TextureSystem only when an image is used.
  SceneTextures& textures() {
    if (!w_.textures) {
      w_.textures = std::make_unique<SceneTextures>(scene_, options_.texture_system);
      w_.features |= kFeatureTextures;
    }
    return *w_.textures;
  }
  void add_textures() {
    if (!scene_.textures.empty()) textures();
  }

  int bind_textures(const std::vector<int>& textures_of_shape, int material, const Transform& to_world) {
    if (textures_of_shape.empty() && !material_needs_textures(scene_, material)) return -1;
    return textures().bind(scene_, textures_of_shape, material, to_world);
  }

  // Participating media: built only when a shape bounds one or a camera sits in one.
  void add_media() {
    media_ = scene_uses_media(scene_);
    if (!media_) return;
    build_world_media(scene_, w_);
    w_.features |= kFeatureMedia;
  }

  // The media on a shape's sides; a transition only when the scene's media are built.
  MediumInterface medium_interface(const MediumInterfaceDesc& d, const std::string& name) {
    if (!media_) return MediumInterface{};
    for (const int m : {d.inside, d.outside})
      if (m < -1 || m >= int(w_.media.size()))
        throw Error(scene_.source_path, name, "names a medium that does not exist");
    if (d.inside != d.outside) ++w_.stats.medium_boundaries;
    return MediumInterface{d.inside, d.outside};
  }

  // Surfaces whose material only marks a boundary (pbrt's "interface") change no ray unless they bound a medium:
  // those are left out of the geometry, so they neither stop camera rays nor shadow lights.
  bool invisible(int material, const std::optional<Rgb>& emission, const MediumInterfaceDesc& sides) {
    const bool emits = emission && !emission->is_black();
    if (emits || material < 0 || size_t(material) >= w_.materials.size() ||
        !w_.materials[size_t(material)].passes_through)
      return false;
    if (media_ && sides.inside != sides.outside) return false;
    ++w_.stats.interface_shapes;
    return true;
  }

  // An emitting shape's light; its index for ShapeData::light.
  template <typename L>
  int add_shape_light(L&& light, size_t& count, uint32_t feature) {
    w_.lights.emplace_back(std::forward<L>(light));
    ++count;
    w_.features |= feature;
    return int(w_.lights.size()) - 1;
  }

  // Meshes: world-space copies for the scene, object-space prototypes for instanced bases.
  void add_meshes() {
    prototype_of_.assign(scene_.meshes.size(), -1);
    for (size_t i = 0; i < scene_.meshes.size(); ++i) {
      const MeshDesc& m = scene_.meshes[i];
      if (m.is_instance_base) {
        prototype_of_[i] = int(w_.geometry.prototypes.size());
        w_.geometry.prototypes.push_back(TriangleMesh{with_spare_capacity(m.positions), with_spare_capacity(m.indices)});
      }
      MeshArrays* arrays = taken_ && (*taken_)[i] ? &*(*taken_)[i] : nullptr;
      if (!m.visible || (!arrays && m.indices.empty())) continue;  // taken arrays are never empty
      check_material(scene_, m.material, m.name, m.emission.has_value());
      if (invisible(m.material, m.emission, m.media)) continue;
      add_mesh(m, arrays);
      if (arrays) (*taken_)[i].reset();  // frees what the world did not keep (e.g. an untextured mesh's uvs)
    }
  }

  // One mesh from its description, its arrays moved from `taken` when given, else copied.
  void add_mesh(const MeshDesc& m, MeshArrays* taken) {
    const std::vector<Vec3f>& normals = taken ? taken->normals : m.normals;
    const std::vector<Vec2f>& uvs = taken ? taken->uvs : m.uvs;
    const bool has_uvs = !uvs.empty() && uvs.size() == (taken ? taken->positions : m.positions).size();
    TriangleMesh tm = taken ? TriangleMesh{take_transformed_points(taken->positions, m.to_world),
                                           take_with_spare_capacity(taken->indices)}
                            : TriangleMesh{transformed_points(m.positions, m.to_world), with_spare_capacity(m.indices)};
    ShapeData sd;
    sd.material = m.material;
    sd.media = medium_interface(m.media, m.name);
    sd.smooth = m.smooth || !normals.empty();
    sd.textures = bind_textures(m.textures, m.material, m.to_world);
    if (m.emission && !m.emission->is_black())  // before the uvs may be moved into the world
      sd.light = add_shape_light(mesh_light(m, tm, has_uvs ? std::span<const Vec2f>(uvs) : std::span<const Vec2f>()),
                                 w_.stats.mesh_lights, kFeatureMeshLights);
    if (has_uvs && (sd.textures >= 0 || m.alpha.texture >= 0)) {  // alpha textures read uvs too
      sd.uvs = int(w_.uvs.size());
      if (taken) w_.uvs.push_back(std::move(taken->uvs));
      else w_.uvs.push_back(uvs);
    }
    if (!normals.empty()) {
      std::vector<Vec3f> n;
      if (taken) n = std::move(taken->normals);
      else n = normals;
      for (Vec3f& v : n) {
        const Vec3f wn = m.to_world.normal(v);
        const float len = length(wn);
        v = len > 0.0f ? wn / len : Vec3f(0.0f);
      }
      sd.normals = int(w_.normals.size());
      w_.normals.push_back(std::move(n));
    } else if (m.smooth) {
      sd.normals = int(w_.normals.size());
      w_.normals.push_back(vertex_normals(tm));
    }
    if (sd.smooth) w_.features |= kFeatureSmoothNormals;
    w_.stats.triangles += tm.triangle_count();
    ++w_.stats.meshes;
    WorldGeometry& g = w_.geometry;
    add_alpha(uint32_t(g.shapes.size()), m.alpha, sd.uvs, m.name, sd.light >= 0);
    g.shapes.push_back(Shape{ShapeKind::Mesh, uint32_t(g.meshes.size()), shape_motion(w_, m.name, m.motion, sd.light)});
    g.meshes.push_back(std::move(tm));
    w_.shape_data.push_back(sd);
    w_.features |= kFeatureTriangles;
  }

  // A mesh's light: its radiance, or its emission image over its (u, v) (pbrt's default (u, v) without uvs).
  MeshLight mesh_light(const MeshDesc& m, const TriangleMesh& tm, std::span<const Vec2f> uvs) {
    if (!m.emission_image) return MeshLight(tm.p, tm.idx, *m.emission, m.two_sided_emission);
    return MeshLight(tm.p, tm.idx, emission_images_.get(*m.emission_image, *m.emission), triangle_uvs(tm.idx, uvs),
                     m.two_sided_emission);
  }

  QuadricLight quadric_light(const QuadricDesc& q) {
    if (!q.emission_image) return QuadricLight(q.quadric, q.to_world, q.flip, *q.emission, q.two_sided_emission);
    return QuadricLight(q.quadric, q.to_world, q.flip, emission_images_.get(*q.emission_image, *q.emission),
                        q.two_sided_emission);
  }

  void add_spheres() {
    WorldGeometry& g = w_.geometry;
    for (const SphereDesc& s : scene_.spheres) {
      check_material(scene_, s.material, s.name, s.emission.has_value());
      if (invisible(s.material, s.emission, s.media)) continue;
      if (s.alpha.cuts() && s.radius > 0.0f) {
        if (!s.emission || s.emission->is_black()) {
          cut_spheres_.push_back(quadric_of_sphere(s));
          continue;
        }
        add_alpha(0, s.alpha, -1, s.name, true);  // warns: the emitter stays opaque
      }
      ShapeData sd;
      sd.material = s.material;
      sd.media = medium_interface(s.media, s.name);
      sd.textures = bind_textures(s.textures, s.material, s.to_world);
      const bool emits = s.emission && !s.emission->is_black();
      if (emits && !(s.radius > 0.0f)) {
        w_.warnings.push_back(s.name + ": zero-radius light sphere emits nothing; left out of the lights");
      } else if (emits) {
        sd.light = add_shape_light(SphereLight(s.center, s.radius, s.to_world, *s.emission, options_.ellipsoid_pdf),
                                   w_.stats.sphere_lights, kFeatureSphereLights);
        w_.stats.cone_sampler_built = true;
      }
      g.shapes.push_back(Shape{ShapeKind::Sphere, uint32_t(g.spheres.size()), shape_motion(w_, s.name, s.motion, sd.light),
                               shape_animation(w_, s.name, s.to_world, s.to_world_motion, sd.light)});
      g.spheres.push_back(SphereShape{s.center, s.radius, s.to_world});
      w_.shape_data.push_back(sd);
      w_.features |= kFeatureSpheres;
    }
    w_.stats.spheres = g.spheres.size();
    w_.stats.sphere_geometry_built = !g.spheres.empty();
  }

  // pbrt's disks, cylinders and partial spheres, then the spheres that have an alpha cut-out.
  void add_quadrics() {
    WorldGeometry& g = w_.geometry;
    const std::vector<QuadricDesc>& cut_spheres = cut_spheres_;
    for (const std::vector<QuadricDesc>* list : {&scene_.quadrics, &cut_spheres})
      for (const QuadricDesc& q : *list) {
        check_material(scene_, q.material, q.name, q.emission.has_value());
        if (invisible(q.material, q.emission, q.media)) continue;
        ShapeData sd;
        sd.material = q.material;
        sd.media = medium_interface(q.media, q.name);
        if (q.emission && !q.emission->is_black())
          sd.light = add_shape_light(quadric_light(q), w_.stats.quadric_lights, kFeatureQuadricLights);
        add_alpha(uint32_t(g.shapes.size()), q.alpha, -1, q.name, sd.light >= 0);
        g.shapes.push_back(Shape{ShapeKind::Quadric, uint32_t(g.quadrics.size()),
                                 shape_motion(w_, q.name, q.motion, sd.light),
                                 shape_animation(w_, q.name, q.to_world, q.to_world_motion, sd.light)});
        g.quadrics.push_back(QuadricShape{q.quadric, q.to_world, q.flip});
        w_.shape_data.push_back(sd);
        w_.features |= kFeatureQuadrics;
      }
    w_.stats.quadrics = g.quadrics.size();
  }

  // Object-space smooth normals and uvs of instanced prototypes, shared by all instances of one prototype.
  void add_instances() {
    WorldGeometry& g = w_.geometry;
    std::vector<int> prototype_normals(g.prototypes.size(), -2);
    std::vector<int> prototype_uvs(g.prototypes.size(), -1);
    for (const InstanceDesc& inst : scene_.instances) {
      if (inst.base_mesh < 0 || size_t(inst.base_mesh) >= scene_.meshes.size() ||
          prototype_of_[size_t(inst.base_mesh)] < 0)
        throw Error(scene_.source_path, inst.name, "references a mesh that is not an instance base");
      const MeshDesc& base = scene_.meshes[size_t(inst.base_mesh)];
      const int proto = prototype_of_[size_t(inst.base_mesh)];
      ShapeData sd;
      sd.material = inst.material >= 0 ? inst.material : base.material;
      check_material(scene_, sd.material, inst.name, false);
      if (invisible(sd.material, std::nullopt, inst.media)) continue;
      sd.media = medium_interface(inst.media, inst.name);
      sd.smooth = inst.smooth.value_or(base.smooth || !base.normals.empty());
      if (sd.smooth) {
        int& pn = prototype_normals[size_t(proto)];
        if (pn == -2) {
          pn = int(w_.normals.size());
          w_.normals.push_back(base.normals.empty() ? vertex_normals(g.prototypes[size_t(proto)]) : base.normals);
        }
        sd.normals = pn;
        w_.features |= kFeatureSmoothNormals;
      }
      sd.textures = bind_textures(inst.textures, sd.material, inst.to_world);
      const bool reads_uvs = sd.textures >= 0 || base.alpha.texture >= 0;
      if (reads_uvs && !base.uvs.empty() && base.uvs.size() == base.positions.size()) {
        int& pu = prototype_uvs[size_t(proto)];
        if (pu == -1) {
          pu = int(w_.uvs.size());
          w_.uvs.push_back(base.uvs);
        }
        sd.uvs = pu;
      }
      add_alpha(uint32_t(g.shapes.size()), base.alpha, sd.uvs, inst.name, false);
      g.shapes.push_back(Shape{ShapeKind::Instance, uint32_t(g.instances.size()),
                               shape_motion(w_, inst.name, inst.motion, -1),
                               shape_animation(w_, inst.name, inst.to_world, inst.to_world_motion, -1)});
      g.instances.push_back(MeshInstance{uint32_t(proto), inst.to_world});
      w_.shape_data.push_back(sd);
      w_.stats.triangles += g.prototypes[size_t(proto)].triangle_count();
      w_.features |= kFeatureInstances;
    }
    w_.stats.instances = g.instances.size();
  }

  // Records a shape's alpha cut-out (shape: its index, about to be added) and compiles its texture. An emitter keeps
  // its surface opaque: its light samples would otherwise fall into the holes.
  void add_alpha(uint32_t shape, const ShapeAlphaDesc& alpha, int uvs, const std::string& name, bool emits) {
    if (!alpha.cuts()) return;
    if (emits) {
      w_.warnings.push_back(name + ": \"alpha\" on an emitting shape is not rendered; the emitter is opaque");
      return;
    }
    if (alpha.texture >= 0) textures().use_pbrt_texture(alpha.texture);
    if (!w_.alpha) w_.alpha = std::make_unique<AlphaCutouts>();
    w_.alpha->add(shape, ShapeAlpha{alpha, uvs});
    w_.features |= kFeatureAlpha;
  }

  // The accelerators' alpha test, only when some shape has a cut-out (the others pay nothing).
  void add_alpha_test() {
    if (!w_.alpha) return;
    WorldGeometry& g = w_.geometry;
    g.alpha = AlphaTest{&AlphaCutouts::opacity, &w_};
    for (uint32_t i = 0; i < g.shapes.size(); ++i) g.shapes[i].alpha = w_.alpha->has(i);
    w_.stats.alpha_shapes = w_.alpha->size();
  }

  // The lights that are not shapes (after the shapes: directional and infinite lights need the scene's radius), then
  // the light sampler over all of them.
  void add_lights() {
    WorldStats& st = w_.stats;
    for (const PointLightDesc& l : scene_.point_lights) add_light(PointLight(l.position, l.intensity), st.point_lights);
    for (const SpotLightDesc& l : scene_.spot_lights)
      add_light(SpotLight(l.position, l.direction, l.intensity, l.coverage_deg, l.falloff_deg,
                          l.falloff == SpotFalloff::SmoothStep),
                st.spot_lights);
    for (const DirectionalLightDesc& l : scene_.directional_lights)
      add_light(DirectionalLight(l.direction, l.radiance, w_.scene_radius), st.directional_lights);
    if (st.point_lights + st.spot_lights + st.directional_lights > 0) w_.features |= kFeaturePointLights;
    for (const AreaLightDesc& l : scene_.area_lights) {
      add_light(make_area_light(l), st.area_lights);
      w_.features |= kFeatureAreaLights;
    }
    for (const InfiniteLightDesc& l : scene_.infinite_lights) {
      w_.infinite_lights.push_back(int(w_.lights.size()));
      add_light(InfiniteLight(l.radiance, w_.scene_radius), st.infinite_lights);
      w_.features |= kFeatureInfiniteLights;
    }
    for (const EnvLightDesc& l : scene_.env_lights) {
      w_.infinite_lights.push_back(int(w_.lights.size()));
      add_light(make_environment_light(scene_, l, w_.scene_radius, options_.env_map_sampling, w_.warnings),
                st.environment_maps);
      w_.features |= kFeatureInfiniteLights | kFeatureEnvironmentMap;
    }
    if (!w_.lights.empty()) {
      w_.light_sampler = LightSampler(w_.lights, options_.light_sampler.value_or(default_light_sampler(w_.lights)));
      st.light_sampler_built = true;
      st.light_sampler = w_.light_sampler.stats();
    }
  }

  template <typename L>
  void add_light(L&& light, size_t& count) {
    w_.lights.emplace_back(std::forward<L>(light));
    ++count;
  }

  const SceneDesc& scene_;
  const WorldOptions& options_;
  std::vector<std::optional<MeshArrays>>* taken_;
  std::vector<QuadricDesc> cut_spheres_;  // spheres with an alpha cut-out, built as quadric spheres
  EmissionImages emission_images_{scene_};
  std::unique_ptr<World> world_;
  World& w_;
  std::vector<int> prototype_of_;  // mesh index -> index into WorldGeometry::prototypes, or -1
  bool media_ = false;             // the scene's media are built (add_media)
};

// Moves the arrays the world keeps out of every visible mesh that is not an instance base (instances read their
// base from the description).
std::vector<std::optional<MeshArrays>> take_mesh_arrays(SceneDesc& scene) {
  std::vector<std::optional<MeshArrays>> taken(scene.meshes.size());
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    MeshDesc& m = scene.meshes[i];
    if (m.is_instance_base || !m.visible || m.indices.empty()) continue;
    taken[i] = MeshArrays{std::exchange(m.positions, {}), std::exchange(m.indices, {}), std::exchange(m.normals, {}),
                          std::exchange(m.uvs, {})};
  }
  return taken;
}

}  // namespace

std::unique_ptr<World> build_world(const SceneDesc& scene, const WorldOptions& options) {
  return WorldBuilder(scene, options, nullptr).build();
}

std::unique_ptr<World> build_world_taking_meshes(SceneDesc& scene, const WorldOptions& options) {
  std::vector<std::optional<MeshArrays>> taken = take_mesh_arrays(scene);
  return WorldBuilder(scene, options, &taken).build();
}

}  // namespace kiln
