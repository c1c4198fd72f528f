#include "renderer/world/hit_textures.h"

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

}  // namespace

UvFootprint hit_footprint(const CameraSpread& camera, const SurfaceInteraction& si) {
  Vec3f dpdx, dpdy;
  approximate_dp_dxy(camera, si.p, si.ng, dpdx, dpdy);
  return uv_footprint(dpdx, dpdy, si.dpdu, si.dpdv);
}

bool apply_textures(const SceneTextures& tex, const CameraSpread& camera, SurfaceInteraction& si, Material& scratch,
                    Rgb& unlit) {
  const TextureBinding& b = tex.bindings()[size_t(si.textures)];
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
