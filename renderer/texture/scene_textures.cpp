#include "renderer/texture/scene_textures.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "core/error.h"
#include "core/frame.h"
#include "renderer/texture/bump_map.h"
#include "renderer/texture/checkerboard.h"
#include "renderer/texture/perlin.h"
#include "scenes/material_mapping.h"

namespace kiln {
namespace {


Rgb degamma(Rgb c) { return pow(c, kDegammaExponent); }

// Unit tangent along dp/du in the plane of n, and the bitangent n x t turned towards dp/dv.
void tangent_frame(Vec3f n, Vec3f dpdu, Vec3f dpdv, Vec3f& t, Vec3f& b) {
  t = dpdu - n * dot(dpdu, n);
  if (length_squared(t) > 0.0f) {
    t = normalize(t);
    b = cross(n, t);
    if (dot(b, dpdv) < 0.0f) b = -b;
  } else {
    coordinate_system(n, t, b);
  }
}

TextureInterp interp_of(TextureFilter f) {
  switch (f) {
    case TextureFilter::Nearest: return TextureInterp::Closest;
    case TextureFilter::Bilinear: return TextureInterp::Bilinear;
    case TextureFilter::Trilinear: return TextureInterp::Trilinear;
    case TextureFilter::Ewa: return TextureInterp::Anisotropic;
  }
  return TextureInterp::Bilinear;
}

bool filtered(const CompiledTexture& t) {
  return t.source == TextureSource::Image &&
         (t.query.interp == TextureInterp::Trilinear || t.query.interp == TextureInterp::Anisotropic);
}

}  // namespace

SceneTextures::SceneTextures(const SceneDesc& scene, const TextureSystemOptions& options)
    : images_(options), graph_(scene.pbrt_textures, scene.source_path, images_) {
  textures_.reserve(scene.textures.size());
  for (const TextureDesc& d : scene.textures) {
    CompiledTexture t;
    t.source = d.source;
    t.decal = d.decal;
    t.bump = d.bump;
    t.bump_factor = d.bump_factor;
    t.degamma = d.degamma;
    t.noise = d.noise;
    t.noise_scale = d.noise_scale;
    t.checker_scale = d.checker_scale;
    t.checker_offset = d.checker_offset;
    t.black = d.black;
    t.white = d.white;
    t.normalizer = d.normalizer.value_or(1.0f);
    if (d.source == TextureSource::Image) {
      const OpenedImage image = images_.open(d.image_path, TextureDecode{}, scene.source_path, d.name);
      const TextureFileInfo& info = image.info;
      t.handle = image.handle;
      t.query.interp = interp_of(d.filter);
      t.query.wrap = d.wrap == TextureWrap::Clamp ? TextureWrapMode::Clamp : TextureWrapMode::Periodic;
      t.value_scale = info.format_max / d.normalizer.value_or(info.format_max);
      t.grey = info.channels < 3;
      if (filtered(t)) ++stats_.filtered;
      t.width = std::max(info.width, 1);
      t.height = std::max(info.height, 1);
      ++stats_.images;
    } else {
      ++stats_.procedural;
    }
    textures_.push_back(t);
  }
  stats_.textures = textures_.size();
  if (scene.background_texture) background_ = *scene.background_texture;
  material_of_desc_.assign(scene.materials.size() * 4, -1);
  pbrt_material_of_desc_.assign(scene.materials.size(), -1);
}

SceneTextures::~SceneTextures() = default;

namespace {

// The materials a hit on `material` may shade with: itself, or a mix's components (through nested mixes; the loader
// and the world reject mixes that contain each other, `depth` stops a cycle that reaches here anyway). on_plain(i, m)
// is called on each of them, on_mix(mix) on every mix on the way.
template <typename F, typename G>
void visit_shading_materials(const SceneDesc& scene, int material, F&& on_plain, G&& on_mix, int depth = 0) {
  if (material < 0 || size_t(material) >= scene.materials.size() || depth > int(scene.materials.size())) return;
  const MaterialDesc& m = scene.materials[size_t(material)];
  if (!m.mix) {
    on_plain(material, m);
    return;
  }
  on_mix(*m.mix);
  for (int c : m.mix->materials) visit_shading_materials(scene, c, on_plain, on_mix, depth + 1);
}

bool pbrt_per_hit(const MaterialDesc& m) { return m.pbrt && needs_per_hit_evaluation(*m.pbrt); }

}  // namespace

bool material_needs_textures(const SceneDesc& scene, int material) {
  bool needs = false;
  visit_shading_materials(
      scene, material, [&](int, const MaterialDesc& m) { needs = needs || pbrt_per_hit(m); },
      [&](const MaterialMixDesc& mix) { needs = needs || mix.amount.textured(); });
  return needs;
}

int SceneTextures::use_pbrt_material(const SceneDesc& scene, int material) {
  int& slot = pbrt_material_of_desc_[size_t(material)];
  if (slot < 0) {
    pbrt_materials_.push_back(make_textured_material(*scene.materials[size_t(material)].pbrt, graph_));
    slot = int(pbrt_materials_.size()) - 1;
  }
  return slot;
}

TextureBuildStats SceneTextures::stats() const {
  TextureBuildStats s = stats_;
  s.texture_system_built = images_.built();
  s.cache_limit_mb = images_.built() ? images_.cache_limit_mb() : 0.0f;
  s.pbrt = graph_.stats();
  s.textured_materials = pbrt_materials_.size();
  return s;
}

int SceneTextures::bind(const SceneDesc& scene, const std::vector<int>& textures, int material,
                        const Transform& to_world) {
  TextureBinding b;
  b.to_object = to_world.inverse();
  bool any = false;
  for (const int i : textures) {
    const CompiledTexture& t = textures_[size_t(i)];
    switch (t.decal) {
      case DecalMode::ReplaceKd: b.kd = i, b.blend_kd = false, any = true; break;
      case DecalMode::BlendKd: b.kd = i, b.blend_kd = true, any = true; break;
      case DecalMode::ReplaceKs: b.ks = i, any = true; break;
      case DecalMode::ReplaceAll: b.all = i, any = true; break;
      case DecalMode::ReplaceNormal: b.normal = i, any = true; break;
      case DecalMode::BumpNormal: break;  // a pure height field: bump below
      case DecalMode::ReplaceBackground: break;
    }
    if (t.bump) b.bump = i, any = true;
  }
  if (material_needs_textures(scene, material)) {
    visit_shading_materials(
        scene, material,
        [&](int c, const MaterialDesc& m) {
          if (pbrt_per_hit(m)) b.pbrt_material = use_pbrt_material(scene, c);
        },
        [&](const MaterialMixDesc& mix) {
          if (mix.amount.textured()) graph_.use(mix.amount.texture);
        });
    b.pbrt_mix = bool(scene.materials[size_t(material)].mix);
    any = true;
  }
  if (!any) return -1;
  for (const int i : {b.kd, b.ks, b.all})
    if (i >= 0 && filtered(textures_[size_t(i)])) b.footprint = true;
  if (b.footprint) ++stats_.footprint_bindings;
  if ((b.kd >= 0 || b.ks >= 0) && material >= 0 && !scene.materials[size_t(material)].pbrt) {
    const int roles = (b.kd >= 0 ? 1 : 0) | (b.ks >= 0 ? 2 : 0);
    int& slot = material_of_desc_[size_t(material) * 4 + size_t(roles)];
    if (slot < 0) {
      // Placeholder reflectances keep the lobes a texture sets from being left out as black.
      MaterialDesc desc = scene.materials[size_t(material)];
      const Rgb own_kd = desc.degamma ? degamma(desc.diffuse) : desc.diffuse;
      const Rgb own_ks = desc.degamma ? degamma(desc.specular) : desc.specular;
      if (roles & 1) desc.diffuse = Rgb(1.0f);
      if (roles & 2) desc.specular = Rgb(1.0f);
      TexturableMaterial tm;
      tm.prototype = build_material(desc, scene);
      tm.kd = own_kd;
      tm.ks = own_ks;
      if (const auto* l = std::get_if<Lambert>(&tm.prototype.surface))
        tm.lambert_scale = (roles & 1) ? l->reflectance.r : (own_kd.r > 0.0f ? l->reflectance.r / own_kd.r : 1.0f);
      slot = int(materials_.size());
      materials_.push_back(std::move(tm));
    }
    b.material = slot;
  }
  bindings_.push_back(b);
  stats_.bindings = bindings_.size();
  return int(bindings_.size()) - 1;
}

Rgb SceneTextures::image_value(const CompiledTexture& t, Vec2f uv, const UvFootprint& fp) const {
  TextureQuery q = t.query;
  q.s = uv.x;
  q.t = uv.y;
  if (filtered(t)) {  // s = u, t = v: the footprint carries over as it is
    q.dsdx = fp.dudx;
    q.dtdx = fp.dvdx;
    q.dsdy = fp.dudy;
    q.dtdy = fp.dvdy;
  }
  float rgb[4];
  images_.lookup(t.handle, q, rgb);
  if (t.grey) rgb[1] = rgb[2] = rgb[0];
  return Rgb(rgb[0], rgb[1], rgb[2]) * t.value_scale;
}

Rgb SceneTextures::value(const CompiledTexture& t, Vec2f uv, Vec3f p, const UvFootprint& fp) const {
  Rgb c(0.0f);
  switch (t.source) {
    case TextureSource::Image: c = image_value(t, uv, fp); break;
    case TextureSource::Perlin: {
      const float n = course_perlin(p * t.noise_scale);
      c = Rgb(t.noise == NoiseConversion::Linear ? 0.5f * (n + 1.0f) : std::fabs(n)) / t.normalizer;
      break;
    }
    case TextureSource::Checkerboard:
      c = (checkerboard_is_white(p, t.checker_offset, t.checker_scale) ? t.white : t.black) / t.normalizer;
      break;
  }
  return t.degamma ? degamma(c) : c;
}

float SceneTextures::height(const CompiledTexture& t, Vec2f uv, Vec3f p) const {
  const Rgb c = value(t, uv, p);
  return (c.r + c.g + c.b) / 3.0f;
}

Vec3f SceneTextures::bumped_normal(const CompiledTexture& t, Vec3f n, Vec2f uv, Vec3f p, Vec3f dpdu,
                                   Vec3f dpdv) const {
  if (t.source == TextureSource::Perlin) {
    // h = (n + 1) / 2 or |n| of the noise at scale * p: the surface moves along the normal by bump_factor * h, and
    // the normal tilts against the tangential part of grad h.
    const Vec3f q = p * t.noise_scale;
    const float dh_dn = t.noise == NoiseConversion::Linear ? 0.5f : (course_perlin(q) < 0.0f ? -1.0f : 1.0f);
    const Vec3f g = course_perlin_gradient(q) * (dh_dn * t.noise_scale / t.normalizer);
    return unit_on_side(n - (g - n * dot(g, n)) * t.bump_factor, n);
  }
  // Images (and the checkerboard, whose height is flat but for its edges): central differences one texel apart,
  // i.e. the height change per texel along u and v, tilting the normal against the tangent and bitangent.
  Vec3f tu, tv;
  tangent_frame(n, dpdu, dpdv, tu, tv);
  const float du = 1.0f / float(t.width), dv = 1.0f / float(t.height);
  const float gu = 0.5f * (height(t, {uv.x + du, uv.y}, p) - height(t, {uv.x - du, uv.y}, p));
  const float gv = 0.5f * (height(t, {uv.x, uv.y + dv}, p) - height(t, {uv.x, uv.y - dv}, p));
  return unit_on_side(n - (tu * gu + tv * gv) * t.bump_factor, n);
}

Vec3f SceneTextures::mapped_normal(const CompiledTexture& t, Vec3f n, Vec2f uv, Vec3f p, Vec3f dpdu) const {
  // Texel c in [0, 1] encodes the tangent-space normal 2c - 1: x along dp/du, y along n x dp/du, z along n.
  const Rgb c = value(t, uv, p);
  Vec3f tu, tv;
  tangent_frame(n, dpdu, cross(n, dpdu), tu, tv);
  return unit_on_side(tu * (2.0f * c.r - 1.0f) + tv * (2.0f * c.g - 1.0f) + n * (2.0f * c.b - 1.0f), n);
}

}  // namespace kiln
