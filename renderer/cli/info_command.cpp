#include <cstdio>
#include <map>

#include "renderer/cli/commands.h"
#include "renderer/integrators/integrator.h"
#include "renderer/render/scene_fingerprint.h"
#include "renderer/world/world.h"
#include "renderer/texture/scene_textures.h"
#include "scenes/loader.h"

namespace kiln {
namespace {

const char* brdf_name(BrdfKind k) {
  switch (k) {
    case BrdfKind::OriginalPhong: return "OriginalPhong";
    case BrdfKind::ModifiedPhong: return "ModifiedPhong";
    case BrdfKind::OriginalBlinnPhong: return "OriginalBlinnPhong";
    case BrdfKind::ModifiedBlinnPhong: return "ModifiedBlinnPhong";
    case BrdfKind::TorranceSparrow: return "TorranceSparrow";
    case BrdfKind::Lambert: return "Lambert";
  }
  return "?";
}

const char* material_type_name(MaterialType t) {
  switch (t) {
    case MaterialType::Plain: return "plain";
    case MaterialType::Mirror: return "mirror";
    case MaterialType::Dielectric: return "dielectric";
    case MaterialType::Conductor: return "conductor";
  }
  return "?";
}

// Every medium with what it was built into, the shapes bounding media and the cameras inside one; media the scene
// defines but never uses are not built.
void print_media(const SceneDesc& s, const World& w) {
  if (s.media.empty()) return;
  const WorldStats& ws = w.stats;
  std::printf("media: %zu defined, %s\n", s.media.size(),
              w.media.empty() ? "none used (not built)" : "built for the volumetric path tracer");
  for (size_t i = 0; i < s.media.size(); ++i)
    std::printf("  medium %zu \"%s\": %s\n", i, s.media[i].name.c_str(),
                i < ws.media.size() ? ws.media[i].c_str() : "(not built)");
  if (w.media.empty()) return;
  std::printf("  %zu shapes bound media, majorant grids %zu voxels, NanoVDB grids %.1f MiB\n", ws.medium_boundaries,
              ws.majorant_voxels, double(ws.medium_grid_bytes) / (1024.0 * 1024.0));
  for (const CameraDesc& c : s.cameras)
    if (c.medium >= 0) std::printf("  camera %s sits in medium %d\n", c.id.c_str(), c.medium);
}

// "light sampler: bvh (512 emitters, a 4-wide tree of 190 nodes, depth 6; 0 beside the tree; 42 KB, built in 0.3 ms)".
void print_light_sampler(const WorldStats& ws) {
  if (!ws.light_sampler_built) {
    std::printf("light sampler: none (no lights)\n");
    return;
  }
  const LightSamplerStats& l = ws.light_sampler;
  std::printf("light sampler: %s", light_sampler_name(l.kind));
  if (l.kind == LightSamplerKind::Bvh)
    std::printf(" (%zu emitters, a 4-wide tree of %zu nodes, depth %d; %zu beside the tree; %.0f KB, built in %.2f ms)", l.emitters,
                l.nodes, l.depth, l.infinite_lights, double(l.bytes) / 1024.0, l.build_seconds * 1e3);
  std::printf("\n");
}

// The scene's identity as `kiln merge` checks it (renderer/render/scene_fingerprint.h): every file it covers.
void print_identity(const SceneFingerprint& f) {
  std::printf("identity: %s (%zu files, %llu bytes)\n", f.hash.c_str(), f.files.size(), (unsigned long long)f.bytes);
  for (const FingerprintedFile& file : f.files)
    std::printf("  %s %12llu  %s\n", file.hash.c_str(), (unsigned long long)file.bytes, file.name.c_str());
}

}  // namespace

int cmd_info(const std::string& path, int subdivide, const RuleOverrides& overrides) {
  LoadOptions lo;
  lo.subdivide = subdivide;
  SceneFingerprint fingerprint;
  const SceneDesc s = load_scene_fingerprinted(path, lo, fingerprint);
  const SceneRules rules = resolve_rules(s, overrides);
  WorldOptions wo;
  wo.build_accelerator = false;
  wo.ellipsoid_pdf = ellipsoid_pdf(rules, overrides);
  wo.env_map_sampling = env_map_sampling(rules, overrides);
  wo.light_sampler = light_sampler_kind(rules, overrides);
  const auto world = build_world(s, wo);
  std::printf("scene: %s (%s)\n", path.c_str(), s.format.c_str());
  std::printf("rules: %s\n", rules_name(rules));
  std::printf("cameras: %zu\n", s.cameras.size());
  for (const CameraDesc& c : s.cameras) {
    const IntegratorSettings is = camera_settings(c, s, rules, overrides, world->features);
    std::printf("  camera %s: %dx%d, %d spp, %s -> %s%s\n", c.id.c_str(), c.width, c.height, c.num_samples,
                is.describe().c_str(), c.image_name.c_str(), c.tonemap ? " (Photographic tonemap)" : "");
  }
  size_t triangles = 0, emissive = 0;
  for (const MeshDesc& m : s.meshes) {
    triangles += m.indices.size() / 3;
    if (m.emission) ++emissive;
  }
  std::printf("meshes: %zu (%zu triangles, %zu emissive), spheres: %zu, quadrics: %zu, instances: %zu\n",
              s.meshes.size(), triangles, emissive, s.spheres.size(), s.quadrics.size(), s.instances.size());
  std::map<std::string, int> brdfs;
  for (const BrdfDesc& b : s.brdfs) ++brdfs[std::string(brdf_name(b.kind)) + (b.normalized ? " (normalized)" : "")];
  std::printf("materials: %zu", s.materials.size());
  std::map<std::string, int> types;
  for (const MaterialDesc& m : s.materials) ++types[material_type_name(m.type)];
  for (const auto& [k, v] : types) std::printf(", %d %s", v, k.c_str());
  std::printf("\nbrdfs:");
  if (brdfs.empty()) std::printf(" none (classic Blinn-Phong)");
  for (const auto& [k, v] : brdfs) std::printf(" %s x%d", k.c_str(), v);
  const WorldStats& ws = world->stats;
  std::printf("\ncompiled:");
  for (const auto& [k, v] : ws.compiled_materials) std::printf(" %s x%zu", k.c_str(), v);
  std::printf(
      "\nlights: ambient %s, point %zu, spot %zu, directional %zu, area %zu, mesh %zu, sphere %zu, quadric %zu, env %zu, "
      "infinite %zu\n",
      s.ambient_light.is_black() ? "off" : "on", ws.point_lights, ws.spot_lights, ws.directional_lights, ws.area_lights,
      ws.mesh_lights, ws.sphere_lights, ws.quadric_lights, s.env_lights.size(), s.infinite_lights.size());
  print_light_sampler(ws);
  std::printf("features: %s\n", describe_features(world->features).c_str());
  print_media(s, *world);
  std::printf("needs: spheres %s, quadrics %s, instances %s, alpha test %s, textures %s, cone sampler %s, "
              "time sample %s\n",
              (world->features & kFeatureSpheres) ? "yes" : "no", (world->features & kFeatureQuadrics) ? "yes" : "no",
              (world->features & kFeatureInstances) ? "yes" : "no",
              ws.alpha_shapes > 0 ? ("yes (" + std::to_string(ws.alpha_shapes) + " shapes)").c_str() : "no",
              (world->features & kFeatureTextures) ? "yes" : "no", ws.cone_sampler_built ? "yes" : "no",
              ws.moving_shapes > 0 ? ("yes (" + std::to_string(ws.moving_shapes) + " moving shapes)").c_str() : "no");
  if (world->textures) {
    const TextureBuildStats& t = world->textures->stats();
    std::printf("textures: %zu (%zu image, %zu procedural) on %zu textured shape bindings; OpenImageIO texture system %s",
                t.textures, t.images, t.procedural, t.bindings, t.texture_system_built ? "built" : "not built");
    if (t.texture_system_built) std::printf(" (cache bound %.0f MB)", double(t.cache_limit_mb));
    if (t.filtered > 0)
      std::printf("; %zu filtered over a footprint, computed on %zu bindings", t.filtered, t.footprint_bindings);
    std::printf("\n");
  }
  print_identity(fingerprint);
  for (const std::string& w : world->warnings) std::printf("warning: %s\n", w.c_str());
  for (const std::string& w : s.warnings) std::printf("warning: %s\n", w.c_str());
  for (const std::string& u : s.unsupported) std::printf("not rendered yet: %s\n", u.c_str());
  return 0;
}

}  // namespace kiln
