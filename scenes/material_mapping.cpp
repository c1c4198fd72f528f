#include "scenes/material_mapping.h"

#include <string>

#include "core/error.h"

namespace kiln {
namespace {

class Context {
 public:
  Context(const MaterialDesc& m, const SceneDesc& s) : m_(m), s_(s) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(s_.source_path, "Material id=" + std::to_string(m_.id), what);
  }
  void check_colour(Rgb c, const char* name) const {
    if (!c.is_finite() || c.has_negative()) fail(std::string(name) + " must be finite and non-negative");
  }
  float refraction_index(const char* why) const {
    if (!m_.has_refraction_index) fail(std::string(why) + " needs a RefractionIndex");
    return positive_index(m_.refraction_index, "RefractionIndex");
  }
  float positive_index(float eta, const char* name) const {
    if (!std::isfinite(eta) || !(eta > 0.0f))
      fail(std::string(name) + " must be a positive number, got " + std::to_string(eta));
    return eta;
  }
  float absorption_index() const {
    if (!std::isfinite(m_.absorption_index) || m_.absorption_index < 0.0f)
      fail("AbsorptionIndex must be a non-negative number, got " + std::to_string(m_.absorption_index));
    return m_.absorption_index;
  }

 private:
  const MaterialDesc& m_;
  const SceneDesc& s_;
};

Rgb degamma(Rgb c) { return pow(c, kDegammaExponent); }

PhongVariant variant_of(BrdfKind kind, bool normalized) {
  if (kind == BrdfKind::OriginalPhong || kind == BrdfKind::OriginalBlinnPhong) return PhongVariant::Original;
  return normalized ? PhongVariant::ModifiedNormalized : PhongVariant::Modified;
}

SurfaceBrdf build_surface(const MaterialDesc& m, const SceneDesc& scene, const Context& ctx, Rgb kd, Rgb ks) {
  if (!m.brdf) {
    if (!std::isfinite(m.phong_exponent) || m.phong_exponent < 0.0f)
      ctx.fail("PhongExponent must be a non-negative number, got " + std::to_string(m.phong_exponent));
    if (kd.is_black() && ks.is_black()) return NoSurface{};
    if (ks.is_black()) return Lambert{kd * kPi};  // f = kd without the specular lobe
    return BlinnPhong{kd, ks, m.phong_exponent, PhongVariant::Original};
  }
  if (*m.brdf < 0 || size_t(*m.brdf) >= scene.brdfs.size())
    ctx.fail("BRDF index " + std::to_string(*m.brdf) + " does not name one of the " +
             std::to_string(scene.brdfs.size()) + " BRDFs");
  const BrdfDesc& b = scene.brdfs[size_t(*m.brdf)];
  if (!std::isfinite(b.exponent) || b.exponent < 0.0f)
    ctx.fail("BRDF id=" + std::to_string(b.id) + " Exponent must be a non-negative number, got " +
             std::to_string(b.exponent));
  if (kd.is_black() && ks.is_black()) return NoSurface{};
  // A lobe whose reflectance is zero is left out: without ks, the Phong forms are f = kd (Original, Modified) or
  // kd/pi (normalized), and Torrance-Sparrow without kdfresnel is kd/pi, all a Lambertian of albedo pi * f.
  if (ks.is_black()) {
    const bool normalized = b.kind == BrdfKind::TorranceSparrow || b.kind == BrdfKind::Lambert || b.normalized;
    if (b.kind != BrdfKind::TorranceSparrow || !b.kd_fresnel) return Lambert{normalized ? kd : kd * kPi};
  }
  switch (b.kind) {
    case BrdfKind::OriginalPhong:
    case BrdfKind::ModifiedPhong:
      return Phong{kd, ks, b.exponent, variant_of(b.kind, b.normalized)};
    case BrdfKind::OriginalBlinnPhong:
    case BrdfKind::ModifiedBlinnPhong:
      return BlinnPhong{kd, ks, b.exponent, variant_of(b.kind, b.normalized)};
    case BrdfKind::TorranceSparrow: {
      const float eta = b.refractive_index ? ctx.positive_index(*b.refractive_index, "TorranceSparrow RefractiveIndex")
                                           : ctx.refraction_index("TorranceSparrow BRDF");
      return TorranceSparrow{kd, ks, b.exponent, eta, ctx.absorption_index(), b.kd_fresnel};
    }
    case BrdfKind::Lambert:
      return Lambert{kd};
  }
  return NoSurface{};
}

// ---- pbrt-v4 materials (MaterialDesc::pbrt) ----

const char* pbrt_kind_name(PbrtMaterialKind k) {
  switch (k) {
    case PbrtMaterialKind::Diffuse:
      return "diffuse";
    case PbrtMaterialKind::Conductor:
      return "conductor";
    case PbrtMaterialKind::Dielectric:
      return "dielectric";
    case PbrtMaterialKind::CoatedDiffuse:
      return "coateddiffuse";
    case PbrtMaterialKind::CoatedConductor:
      return "coatedconductor";
    case PbrtMaterialKind::DiffuseTransmission:
      return "diffusetransmission";
    case PbrtMaterialKind::ThinDielectric:
      return "thindielectric";
    case PbrtMaterialKind::Interface:
      return "interface";
  }
  return "?";
}

class PbrtContext {
 public:
  PbrtContext(const Context& ctx, const PbrtMaterialDesc& d) : ctx_(ctx), d_(d) {}
  [[noreturn]] void fail(const std::string& what) const {
    ctx_.fail(std::string("pbrt ") + pbrt_kind_name(d_.kind) + " material: " + what);
  }
  // Finite and non-negative, then clamped to [0, hi] as pbrt-v4 clamps albedo-like spectra.
  Rgb albedo_like(Rgb c, const char* name, float hi = 1.0f) const {
    if (!c.is_finite() || c.has_negative()) fail(std::string(name) + " must be finite and non-negative");
    for (int i = 0; i < 3; ++i) c[i] = std::min(c[i], hi);
    return c;
  }
  float non_negative(float v, const char* name) const {
    if (!std::isfinite(v) || v < 0.0f) fail(std::string(name) + " must be a non-negative number, got " + std::to_string(v));
    return v;
  }
  float positive(float v, const char* name) const {
    if (!std::isfinite(v) || !(v > 0.0f)) fail(std::string(name) + " must be a positive number, got " + std::to_string(v));
    return v;
  }
  TrowbridgeReitz distribution() const { return distribution(d_.uroughness, d_.vroughness, "uroughness", "vroughness"); }
  TrowbridgeReitz distribution(float u, float v, const char* u_name, const char* v_name) const {
    u = non_negative(u, u_name);
    v = non_negative(v, v_name);
    if (!d_.remap_roughness) return TrowbridgeReitz(u, v);
    return TrowbridgeReitz(TrowbridgeReitz::roughness_to_alpha(u), TrowbridgeReitz::roughness_to_alpha(v));
  }
  // The coat (interface index eta, the material's roughness) and the medium under it, checked: the random walk's
  // limits, g in (-1, 1), thickness and albedo.
  LayerStack layers(float eta) const {
    check_layers();
    return LayerStack{RoughDielectric{eta, distribution()}, non_negative(d_.thickness, "thickness"),
                      albedo_like(d_.albedo, "albedo"), d_.g, d_.max_depth, d_.n_samples};
  }
  void check_layers() const {
    if (!std::isfinite(d_.g) || !(std::abs(d_.g) < 1.0f))
      fail("g must lie strictly between -1 and 1, got " + std::to_string(d_.g));
    if (d_.max_depth < 0 || d_.max_depth > kMaxPbrtLayeredDepth)
      fail("maxdepth must be in [0, " + std::to_string(kMaxPbrtLayeredDepth) + "], got " + std::to_string(d_.max_depth));
    if (d_.n_samples < 1 || d_.n_samples > kMaxPbrtLayeredSamples)
      fail("nsamples must be in [1, " + std::to_string(kMaxPbrtLayeredSamples) + "], got " + std::to_string(d_.n_samples));
  }
  RgbComplexIor conductor_ior() const {
    if (d_.conductor_reflectance) {
      // pbrt-v4: eta = 1 and k = 2 sqrt(r) / sqrt(1 - r), whose normal-incidence reflectance is exactly r.
      const Rgb r = albedo_like(*d_.conductor_reflectance, "reflectance", kMaxPbrtConductorReflectance);
      Rgb k;
      for (int i = 0; i < 3; ++i) k[i] = 2.0f * std::sqrt(r[i]) / std::sqrt(1.0f - r[i]);
      return {Rgb(1.0f), k};
    }
    const Rgb eta = d_.conductor_eta, k = d_.conductor_k;
    if (!eta.is_finite() || eta.has_negative()) fail("eta must be finite and non-negative");
    if (!k.is_finite() || k.has_negative()) fail("k must be finite and non-negative");
    return {eta, k};
  }

 private:
  const Context& ctx_;
  const PbrtMaterialDesc& d_;
};

Material build_pbrt_material(const PbrtMaterialDesc& d, const Context& ctx) {
  const PbrtContext p(ctx, d);
  Material out;
  switch (d.kind) {
    case PbrtMaterialKind::Diffuse:
      out.surface = Lambert{p.albedo_like(d.reflectance, "reflectance")};
      break;
    case PbrtMaterialKind::Conductor: {
      const TrowbridgeReitz tr = p.distribution();
      const RgbComplexIor ior = p.conductor_ior();
      if (tr.effectively_smooth())
        out.delta = Conductor{Rgb(1.0f), 1.0f, 0.0f, ior};
      else
        out.surface = RoughConductor{tr, ior};
      break;
    }
    case PbrtMaterialKind::Dielectric: {
      const TrowbridgeReitz tr = p.distribution();
      const float eta = p.positive(d.eta, "eta");
      // eta = 1 is no interface at all (pbrt treats it as a specular pass-through, rough or not).
      if (eta == 1.0f || tr.effectively_smooth())
        out.delta = Dielectric{eta};
      else
        out.surface = RoughDielectric{eta, tr};
      break;
    }
    case PbrtMaterialKind::CoatedDiffuse:
      out.surface =
          CoatedDiffuse{{p.layers(p.positive(d.eta, "eta")), Lambert{p.albedo_like(d.reflectance, "reflectance")}}};
      break;
    case PbrtMaterialKind::CoatedConductor: {
      const float eta = p.positive(d.eta, "interface.eta");
      // The conductor lies under the coat: its index relative to the coat's (pbrt-v4 divides eta and k by it).
      const RgbComplexIor ior = p.conductor_ior();
      const TrowbridgeReitz base = p.distribution(d.conductor_uroughness, d.conductor_vroughness,
                                                  "conductor.uroughness", "conductor.vroughness");
      out.surface = CoatedConductor{{p.layers(eta), RoughConductor{base, {ior.eta / eta, ior.k / eta}}}};
      break;
    }
    case PbrtMaterialKind::DiffuseTransmission: {
      const float scale = p.non_negative(d.scale, "scale");
      // pbrt-v4 scales first, then clamps to [0, 1].
      out.surface = DiffuseTransmission{p.albedo_like(d.reflectance * scale, "reflectance"),
                                        p.albedo_like(d.transmittance * scale, "transmittance")};
      break;
    }
    case PbrtMaterialKind::ThinDielectric:
      out.delta = ThinDielectric{p.positive(d.eta, "eta")};
      break;
    case PbrtMaterialKind::Interface:
      out.passes_through = true;
      out.delta = Dielectric{1.0f};
      break;
  }
  return out;
}

// Per-unit-length transmittance a -> Beer-Lambert coefficient -ln(a).
Rgb absorption_from_transparency(Rgb a) {
  Rgb c;
  for (int i = 0; i < 3; ++i) c[i] = -std::log(std::clamp(a[i], kMinTransparency, 1.0f));
  return c;
}

}  // namespace

Material build_material(const MaterialDesc& m, const SceneDesc& scene) {
  const Context ctx(m, scene);
  if (m.mix) return Material{};  // never shaded: the world resolves a mix to one of its components at each hit
  if (m.pbrt) return build_pbrt_material(*m.pbrt, ctx);
  ctx.check_colour(m.ambient, "AmbientReflectance");
  ctx.check_colour(m.diffuse, "DiffuseReflectance");
  ctx.check_colour(m.specular, "SpecularReflectance");
  ctx.check_colour(m.mirror, "MirrorReflectance");
  ctx.check_colour(m.transparency, "Transparency");
  ctx.check_colour(m.absorption_coefficient, "AbsorptionCoefficient");
  if (!std::isfinite(m.roughness) || m.roughness < 0.0f)
    ctx.fail("Roughness must be a non-negative number, got " + std::to_string(m.roughness));

  const bool dg = m.degamma;
  const Rgb ka = dg ? degamma(m.ambient) : m.ambient;
  const Rgb kd = dg ? degamma(m.diffuse) : m.diffuse;
  const Rgb ks = dg ? degamma(m.specular) : m.specular;
  const Rgb km = dg ? degamma(m.mirror) : m.mirror;

  Material out;
  out.ambient = ka;
  out.surface = build_surface(m, scene, ctx, kd, ks);
  out.roughness = m.roughness;
  switch (m.type) {
    case MaterialType::Mirror:
      if (!km.is_black()) out.delta = Mirror{km};
      break;
    case MaterialType::Conductor:
      if (!km.is_black()) out.delta = Conductor{km, ctx.refraction_index("a conductor"), ctx.absorption_index()};
      break;
    case MaterialType::Dielectric:
      out.delta = Dielectric{ctx.refraction_index("a dielectric")};
      out.absorption = m.absorption_coefficient;
      break;
    case MaterialType::Plain:
      if (!m.transparency.is_black()) {
        out.delta = Dielectric{ctx.refraction_index("a dielectric (non-zero Transparency)")};
        out.absorption = absorption_from_transparency(m.transparency) + m.absorption_coefficient;
      } else if (!km.is_black()) {
        out.delta = Mirror{km};
      }
      break;
  }
  return out;
}

}  // namespace kiln
