#include "renderer/world/hit_textures.h"

#include <type_traits>

#include "renderer/texture/bump_map.h"
#include "scenes/material_mapping.h"

namespace kiln {
namespace {

// Reflectances of a copied prototype: k_d / k_s of the course BRDFs, a Lambertian's albedo per unit k_d.
void set_reflectances(Material& m, Rgb kd, Rgb ks, float lambert_scale) {
  if (auto* l = std::get_if<Lambert>(&m.surface)) {
    l->reflectance = kd * lambert_scale;
  } else if (auto* p = std::get_if<Phong>(&m.surface)) {
    p->kd = kd, p->ks = ks;
  } else if (auto* b = std::get_if<BlinnPhong>(&m.surface)) {
    b->kd = kd, b->ks = ks;
  } else if (auto* t = std::get_if<TorranceSparrow>(&m.surface)) {
    t->kd = kd, t->ks = ks;
  }
}

// At a hit (si.uv, si.dpdu, si.dpdv set): bends si.ns by the normal map, else the displacement, and when parameters
// are textured builds `scratch` from their values and points si.material at it. `smooth`: si.ns is interpolated from
// vertex normals (the bump then uses pbrt-v4's shading tangents).
void resolve_textured_material(const TextureGraph& g, const TexturedPbrtMaterial& m, const TextureEvalContext& c,
                               bool smooth, SurfaceInteraction& si, Material& scratch) {
  const PbrtMaterialDesc& d = m.desc;
  if (d.normal_map >= 0 || d.displacement >= 0) {
    Vec3f dpdu = si.dpdu, dpdv = si.dpdv;
    if (smooth) shading_tangents(si.ns, si.dpdu, dpdu, dpdv);
    const Vec3f n = d.normal_map >= 0 ? normal_mapped_normal(g, d.normal_map, c, si.ns, dpdu)
                                      : bump_mapped_normal(g, d.displacement, c, si.ns, dpdu, dpdv);
    si.ns = unit_on_side(n, si.ng);
  }
  if (!m.textured_parameters) return;
  PbrtMaterialDesc evaluated = d;
  for_each_texturable(evaluated, [&](auto& p) {
    if (!p.textured()) return;
    if constexpr (std::is_same_v<std::decay_t<decltype(p)>, TexturedFloat>)
      p.value = g.eval_float(p.texture, c);
    else
      p.value = g.eval_rgb(p.texture, c);
  });
  scratch = build_pbrt_material(evaluated);
  si.material = &scratch;
}

// The hit as pbrt-v4 textures see it; the footprint only when a texture reads it.
TextureEvalContext pbrt_eval_context(const CameraSpread& camera, float footprint_scale, const SurfaceInteraction& si,
                                     bool footprint) {
  TextureEvalContext c;
  c.p = si.p;
  c.n = si.ng;
  c.uv = si.uv;
  if (footprint) {
    approximate_dp_dxy(camera, si.p, si.ng, c.dpdx, c.dpdy);
    c.dpdx = c.dpdx * footprint_scale;
    c.dpdy = c.dpdy * footprint_scale;
    c.fp = uv_footprint(c.dpdx, c.dpdy, si.dpdu, si.dpdv);
  }
  return c;
}

// The plain material a hit on shape material `material` shades with, finishing the mixes' choice that
// make_interaction stopped at a textured amount (renderer/world/material_mix.h): each textured amount is evaluated
// at the hit, constant ones are taken as they are.
int choose_textured_mix(const World& w, const CameraSpread& camera, float footprint_scale, const SurfaceInteraction& si,
                        int material) {
  const TextureGraph& g = w.textures->graph();
  while (w.mixes[size_t(material)].is_mix()) {
    const MaterialMix& m = w.mixes[size_t(material)];
    float amount = m.amount;
    if (m.textured())
      amount = g.eval_float(m.amount_texture,
                            pbrt_eval_context(camera, footprint_scale, si, g.needs_footprint(m.amount_texture)));
    material = mix_component(w.mixes, material, amount, si.p, si.wo);
  }
  return material;
}

}  // namespace

UvFootprint hit_footprint(const CameraSpread& camera, const SurfaceInteraction& si) {
  Vec3f dpdx, dpdy;
  approximate_dp_dxy(camera, si.p, si.ng, dpdx, dpdy);
  return uv_footprint(dpdx, dpdy, si.dpdu, si.dpdv);
}

bool apply_textures(const World& w, const CameraSpread& camera, float pbrt_footprint_scale, SurfaceInteraction& si,
                    Material& scratch, Rgb& unlit) {
  const SceneTextures& tex = *w.textures;
  const TextureBinding& b = tex.bindings()[size_t(si.textures)];
  if (b.pbrt_material >= 0 || b.pbrt_mix) {
    // A mix's hit shades with the component it chose, which may or may not be resolved per hit.
    int pm = b.pbrt_material;
    if (b.pbrt_mix) {
      const int chosen = choose_textured_mix(w, camera, pbrt_footprint_scale, si, int(si.material - w.materials.data()));
      si.material = &w.materials[size_t(chosen)];
      pm = tex.pbrt_material_of(size_t(chosen));
    }
    if (pm < 0) return false;
    const TexturedPbrtMaterial& m = tex.pbrt_materials()[size_t(pm)];
    const bool smooth = w.shape_data[si.shape].normals >= 0;
    const TextureEvalContext c = pbrt_eval_context(camera, pbrt_footprint_scale, si, m.needs_footprint);
    resolve_textured_material(tex.graph(), m, c, smooth, si, scratch);
    return false;
  }
  const Vec3f p = b.to_object.point(si.p);  // where procedural textures are evaluated
  // Only bindings with a filtered colour texture pay for a footprint (bump and normal maps read the finest level).
  const UvFootprint fp = b.footprint ? hit_footprint(camera, si) : UvFootprint{};
  if (b.all >= 0) {
    unlit = tex.value(b.all, si.uv, p, fp);
    return true;
  }
  if (b.normal >= 0) si.ns = tex.mapped_normal(tex.textures()[size_t(b.normal)], si.ns, si.uv, p, si.dpdu);
  if (b.bump >= 0) si.ns = tex.bumped_normal(tex.textures()[size_t(b.bump)], si.ns, si.uv, p, si.dpdu, si.dpdv);
  if (b.material >= 0 && si.material) {
    const TexturableMaterial& tm = tex.materials()[size_t(b.material)];
    scratch = tm.prototype;
    Rgb kd = tm.kd, ks = tm.ks;
    if (b.kd >= 0) {
      const Rgb texel = tex.value(b.kd, si.uv, p, fp);
      kd = b.blend_kd ? (kd + texel) * 0.5f : texel;
    }
    if (b.ks >= 0) ks = tex.value(b.ks, si.uv, p, fp);
    set_reflectances(scratch, kd, ks, tm.lambert_scale);
    si.material = &scratch;
  }
  return false;
}

}  // namespace kiln
