#include <algorithm>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "renderer/cli/commands.h"
#include "renderer/integrators/integrator.h"
#include "renderer/render/scene_fingerprint.h"
#include "renderer/texture/scene_textures.h"
#include "renderer/world/camera.h"
#include "renderer/world/world.h"
#include "scenes/loader.h"

namespace kiln {
namespace {

// Per outcome, the text output lists this many directives of each (directive, feature) and counts the rest
// (--json lists them all).
constexpr size_t kNotesShownPerGroup = 5;

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

const char* projection_name(CameraProjection p) {
  switch (p) {
    case CameraProjection::Perspective: return "perspective";
    case CameraProjection::Orthographic: return "orthographic";
    case CameraProjection::Spherical: return "spherical";
    case CameraProjection::Realistic: return "realistic";
  }
  return "?";
}

const char* outcome_name(LoadOutcome o) {
  switch (o) {
    case LoadOutcome::Rendered: return "rendered";
    case LoadOutcome::Substituted: return "substituted";
    case LoadOutcome::Ignored: return "ignored";
    case LoadOutcome::Remark: return "remark";
  }
  return "?";
}

std::string where(const std::string& file, int line) { return file + ":" + std::to_string(line); }

// Directives of each kind that have a note saying they are not rendered as written (counted once per directive).
std::map<std::string, size_t> not_rendered_as_written(const SceneDesc& s) {
  std::map<std::string, std::map<std::string, int>> seen;  // kind -> directive's location -> 1
  for (const LoadNote& n : s.notes)
    if (n.outcome == LoadOutcome::Substituted || n.outcome == LoadOutcome::Ignored)
      seen[n.kind][where(n.file, n.directive_line)] = 1;
  std::map<std::string, size_t> out;
  for (const auto& [d, locations] : seen) out[d] = locations.size();
  return out;
}

size_t rendered_as_written(const std::map<std::string, size_t>& partial, const std::string& kind,
                           const DirectiveCount& c) {
  const auto it = partial.find(kind);
  const size_t not_as_written = it == partial.end() ? 0 : it->second;
  return c.count > not_as_written ? c.count - not_as_written : 0;
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

struct Loaded {
  SceneFingerprint fingerprint;
  SceneDesc scene;
  SceneRules rules = SceneRules::Kiln;
  RuleOverrides overrides;
  std::unique_ptr<World> world;
};

Loaded load(const InfoArgs& args) {
  LoadOptions lo;
  lo.subdivide = args.subdivide;
  lo.allow_missing_files = args.allow_missing;
  Loaded l;
  l.scene = load_scene_fingerprinted(args.scene, lo, l.fingerprint);
  l.overrides = args.overrides;
  l.rules = resolve_rules(l.scene, l.overrides);
  WorldOptions wo;
  wo.build_accelerator = false;
  wo.ellipsoid_pdf = ellipsoid_pdf(l.rules, l.overrides);
  wo.env_map_sampling = env_map_sampling(l.rules, l.overrides);
  wo.light_sampler = light_sampler_kind(l.rules, l.overrides);
  l.world = build_world(l.scene, wo);
  for (const CameraDesc& c : l.scene.cameras) Camera check(c);  // a lens that cannot focus fails here, not mid-render
  return l;
}

// One line per note, every line self-contained so that surveys can grep it:
//   <outcome>: <file>:<line>: <directive> [<feature>]: <message>
// with <outcome> one of substituted / ignored / remark (remarks have no feature). In file order per outcome; past
// kNotesShownPerGroup notes of one (directive kind, feature), the rest are counted on a line that starts with "...".
void print_notes(const SceneDesc& s, LoadOutcome o) {
  std::map<std::pair<std::string, std::string>, size_t> shown;
  for (const LoadNote& n : s.notes) {
    if (n.outcome != o) continue;
    if (shown[{n.kind, n.feature}]++ >= kNotesShownPerGroup) continue;
    const std::string feature = n.feature.empty() ? "" : " [" + n.feature + "]";
    std::printf("%s: %s: %s%s: %s\n", outcome_name(o), where(n.file, n.line).c_str(), n.directive.c_str(),
                feature.c_str(), n.message.empty() ? n.feature.c_str() : n.message.c_str());
  }
  for (const auto& [key, count] : shown)
    if (count > kNotesShownPerGroup)
      std::printf("... %zu more %s: %s%s (kiln info --json lists every one)\n", count - kNotesShownPerGroup,
                  outcome_name(o), key.first.c_str(), key.second.empty() ? "" : (" [" + key.second + "]").c_str());
}

void print_directives(const SceneDesc& s) {
  size_t total = 0;
  for (const auto& [d, c] : s.directives) total += c.count;
  const auto partial = not_rendered_as_written(s);
  size_t partial_total = 0;
  for (const auto& [d, n] : partial) partial_total += n;
  std::printf("directives: %zu, %zu rendered as written, %zu not (substituted or ignored, below)\n", total,
              total - partial_total, partial_total);
  for (const auto& [d, c] : s.directives) {
    const size_t n = rendered_as_written(partial, d, c);
    if (n > 0) std::printf("rendered: %s x%zu\n", d.c_str(), n);
  }
  for (LoadOutcome o : {LoadOutcome::Substituted, LoadOutcome::Ignored, LoadOutcome::Remark}) print_notes(s, o);
}

// Each feature not rendered as written, once, with how many directives it touches.
void print_unsupported(const SceneDesc& s) {
  std::map<std::string, std::map<std::string, int>> places;  // feature -> location -> 1
  for (const LoadNote& n : s.notes)
    if (!n.feature.empty()) places[n.feature][where(n.file, n.directive_line)] = 1;
  for (const std::string& u : s.unsupported) {
    const size_t n = places[u].size();
    std::printf("not rendered yet: %s (%zu directive%s)\n", u.c_str(), n, n == 1 ? "" : "s");
  }
}

void print_text(const InfoArgs& args, const Loaded& l) {
  const SceneDesc& s = l.scene;
  const World& world = *l.world;
  std::printf("scene: %s (%s)\n", args.scene.c_str(), s.format.c_str());
  std::printf("rules: %s\n", rules_name(l.rules));
  std::printf("cameras: %zu\n", s.cameras.size());
  for (const CameraDesc& c : s.cameras) {
    const IntegratorSettings is = camera_settings(c, s, l.rules, l.overrides, world.features);
    std::printf("  camera %s: %s, %dx%d, %d spp, %s -> %s%s%s\n", c.id.c_str(), projection_name(c.projection), c.width,
                c.height, c.num_samples, is.describe().c_str(), c.image_name.c_str(),
                c.tonemap ? " (Photographic tonemap)" : "", c.motion ? " (moving)" : "");
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
  const WorldStats& ws = world.stats;
  std::printf("\ncompiled:");
  for (const auto& [k, v] : ws.compiled_materials) std::printf(" %s x%zu", k.c_str(), v);
  std::printf(
      "\nlights: ambient %s, point %zu, spot %zu, directional %zu, area %zu, mesh %zu, sphere %zu, quadric %zu, env %zu, "
      "infinite %zu\n",
      s.ambient_light.is_black() ? "off" : "on", ws.point_lights, ws.spot_lights, ws.directional_lights, ws.area_lights,
      ws.mesh_lights, ws.sphere_lights, ws.quadric_lights, s.env_lights.size(), s.infinite_lights.size());
  print_light_sampler(ws);
  std::printf("features: %s\n", describe_features(world.features).c_str());
  print_media(s, world);
  std::printf("needs: spheres %s, quadrics %s, instances %s, alpha test %s, textures %s, cone sampler %s, "
              "time sample %s\n",
              (world.features & kFeatureSpheres) ? "yes" : "no", (world.features & kFeatureQuadrics) ? "yes" : "no",
              (world.features & kFeatureInstances) ? "yes" : "no",
              ws.alpha_shapes > 0 ? ("yes (" + std::to_string(ws.alpha_shapes) + " shapes)").c_str() : "no",
              (world.features & kFeatureTextures) ? "yes" : "no", ws.cone_sampler_built ? "yes" : "no",
              ws.moving_shapes > 0 ? ("yes (" + std::to_string(ws.moving_shapes) + " moving shapes)").c_str() : "no");
  if (world.textures) {
    const TextureBuildStats t = world.textures->stats();
    std::printf("textures: ");
    if (t.textures > 0)
      std::printf("%zu (%zu image, %zu procedural) on %zu textured shape bindings; ", t.textures, t.images,
                  t.procedural, t.bindings);
    std::printf("OpenImageIO texture system %s", t.texture_system_built ? "built" : "not built");
    if (t.texture_system_built) std::printf(" (cache bound %.0f MB)", double(t.cache_limit_mb));
    if (t.filtered > 0)
      std::printf("; %zu filtered over a footprint, computed on %zu bindings", t.filtered, t.footprint_bindings);
    std::printf("\n");
    if (t.pbrt.defined > 0 || t.textured_materials > 0)
      std::printf("pbrt textures: %zu defined, %zu used by rendered materials or alpha (%zu image files); %zu materials "
                  "evaluated per hit\n",
                  t.pbrt.defined, t.pbrt.compiled, t.pbrt.images, t.textured_materials);
    const auto textured_mixes = std::count_if(world.mixes.begin(), world.mixes.end(),
                                              [](const MaterialMix& m) { return m.textured(); });
    if (textured_mixes > 0)
      std::printf("mixes chosen per hit by a textured amount: %zu\n", size_t(textured_mixes));
  } else if (!s.pbrt_textures.empty()) {
    std::printf("pbrt textures: %zu defined, none used by a rendered material (no texture system built)\n",
                s.pbrt_textures.size());
  }
  print_identity(l.fingerprint);
  for (const std::string& w : world.warnings) std::printf("warning: %s\n", w.c_str());
  if (s.directives.empty()) {
    for (const std::string& w : s.warnings) std::printf("warning: %s\n", w.c_str());
  } else {
    print_directives(s);
  }
  print_unsupported(s);
}

void print_json(const InfoArgs& args, const Loaded& l) {
  const SceneDesc& s = l.scene;
  const World& world = *l.world;
  nlohmann::ordered_json j;
  j["scene"] = args.scene;
  j["format"] = s.format;
  j["rules"] = rules_name(l.rules);
  j["identity"] = l.fingerprint.hash;
  j["cameras"] = nlohmann::json::array();
  for (const CameraDesc& c : s.cameras)
    j["cameras"].push_back({{"id", c.id}, {"projection", projection_name(c.projection)}, {"width", c.width},
                            {"height", c.height}, {"spp", c.num_samples}, {"moving", c.motion.has_value()}});
  size_t triangles = 0;
  for (const MeshDesc& m : s.meshes) triangles += m.indices.size() / 3;
  j["meshes"] = s.meshes.size();
  j["triangles"] = triangles;
  j["spheres"] = s.spheres.size();
  j["quadrics"] = s.quadrics.size();
  j["instances"] = s.instances.size();
  j["materials"] = s.materials.size();
  j["textures"] = s.textures.size();
  const WorldStats& ws = world.stats;
  j["lights"] = {{"point", ws.point_lights},   {"spot", ws.spot_lights},     {"directional", ws.directional_lights},
                 {"area", ws.area_lights},     {"mesh", ws.mesh_lights},     {"sphere", ws.sphere_lights},
                 {"quadric", ws.quadric_lights}, {"env", s.env_lights.size()}, {"infinite", s.infinite_lights.size()}};
  j["light_sampler"] = ws.light_sampler_built ? light_sampler_name(ws.light_sampler.kind) : "none";
  j["alpha_shapes"] = ws.alpha_shapes;
  j["moving_shapes"] = ws.moving_shapes;
  j["features"] = describe_features(world.features);
  j["unsupported"] = s.unsupported;
  j["world_warnings"] = world.warnings;
  const auto partial = not_rendered_as_written(s);
  nlohmann::ordered_json directives = nlohmann::ordered_json::object();
  for (const auto& [d, c] : s.directives) {
    directives[d] = {{"count", c.count},
                     {"rendered_as_written", rendered_as_written(partial, d, c)},
                     {"first", where(c.first_file, c.first_line)}};
  }
  j["directives"] = directives;
  j["notes"] = nlohmann::json::array();
  for (const LoadNote& n : s.notes)
    j["notes"].push_back({{"file", n.file}, {"line", n.line}, {"directive", n.directive}, {"kind", n.kind},
                          {"directive_line", n.directive_line},
                          {"outcome", outcome_name(n.outcome)}, {"feature", n.feature}, {"message", n.message}});
  j["warnings"] = s.warnings;
  std::printf("%s\n", j.dump(1).c_str());
}

}  // namespace

int cmd_info(const InfoArgs& args) {
  const Loaded l = load(args);
  if (args.json)
    print_json(args, l);
  else
    print_text(args, l);
  return 0;
}

}  // namespace kiln
