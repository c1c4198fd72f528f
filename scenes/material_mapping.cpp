#include "scenes/material_mapping.h"

#include <algorithm>
#include <limits>
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

// Load-time checks of a pbrt material's constant parameters: bad values name the file, the material and its type.
// Textured parameters are not checked here (their values are only known at a hit, where build_pbrt_material brings
// them into range).
class PbrtCheck {
 public:
  PbrtCheck(const Context& ctx, const PbrtMaterialDesc& d) : ctx_(ctx), d_(d) {}
  [[noreturn]] void fail(const std::string& what) const {
    ctx_.fail(std::string("pbrt ") + pbrt_kind_name(d_.kind) + " material: " + what);
  }
  void colour(const TexturedRgb& c, const char* name) const {
    if (!c.textured() && (!c.value.is_finite() || c.value.has_negative()))
      fail(std::string(name) + " must be finite and non-negative");
  }
  void non_negative(const TexturedFloat& v, const char* name) const {
    if (!v.textured() && (!std::isfinite(v.value) || v.value < 0.0f))
      fail(std::string(name) + " must be a non-negative number, got " + std::to_string(v.value));
  }
  void positive(const TexturedFloat& v, const char* name) const {
    if (!v.textured() && (!std::isfinite(v.value) || !(v.value > 0.0f)))
      fail(std::string(name) + " must be a positive number, got " + std::to_string(v.value));
  }
  void check() const {
    const bool coated = d_.kind == PbrtMaterialKind::CoatedConductor;
    non_negative(d_.uroughness, coated ? "interface.uroughness" : "uroughness");
    non_negative(d_.vroughness, coated ? "interface.vroughness" : "vroughness");
    switch (d_.kind) {
      case PbrtMaterialKind::Diffuse:
        colour(d_.reflectance, "reflectance");
        break;
      case PbrtMaterialKind::Conductor:
        conductor();
        break;
      case PbrtMaterialKind::Dielectric:
      case PbrtMaterialKind::ThinDielectric:
        positive(d_.eta, "eta");
        break;
      case PbrtMaterialKind::CoatedDiffuse:
        layers();
        colour(d_.reflectance, "reflectance");
        positive(d_.eta, "eta");
        break;
      case PbrtMaterialKind::CoatedConductor:
        layers();
        positive(d_.eta, "interface.eta");
        non_negative(d_.conductor_uroughness, "conductor.uroughness");
        non_negative(d_.conductor_vroughness, "conductor.vroughness");
        conductor();
        break;
      case PbrtMaterialKind::DiffuseTransmission:
        if (!std::isfinite(d_.scale) || d_.scale < 0.0f)
          fail("scale must be a non-negative number, got " + std::to_string(d_.scale));
        colour(d_.reflectance, "reflectance");
        colour(d_.transmittance, "transmittance");
        break;
      case PbrtMaterialKind::Interface:
        break;
    }
  }

 private:
  void conductor() const {
    if (d_.conductor_by_reflectance) {
      colour(d_.conductor_reflectance, "reflectance");
    } else {
      colour(d_.conductor_eta, "eta");
      colour(d_.conductor_k, "k");
    }
  }
  // The coated materials' random walk and medium: its limits, g in (-1, 1), thickness and albedo.
  void layers() const {
    if (!d_.g.textured() && (!std::isfinite(d_.g.value) || !(std::abs(d_.g.value) < 1.0f)))
      fail("g must lie strictly between -1 and 1, got " + std::to_string(d_.g.value));
    if (d_.max_depth < 0 || d_.max_depth > kMaxPbrtLayeredDepth)
      fail("maxdepth must be in [0, " + std::to_string(kMaxPbrtLayeredDepth) + "], got " + std::to_string(d_.max_depth));
    if (d_.n_samples < 1 || d_.n_samples > kMaxPbrtLayeredSamples)
      fail("nsamples must be in [1, " + std::to_string(kMaxPbrtLayeredSamples) + "], got " + std::to_string(d_.n_samples));
    colour(d_.albedo, "albedo");
    non_negative(d_.thickness, "thickness");
  }

  const Context& ctx_;
  const PbrtMaterialDesc& d_;
};

// Values brought into their domain (checked constants pass unchanged; a texture may give anything).
float finite_or(float v, float fallback) { return std::isfinite(v) ? v : fallback; }
float non_negative(float v) { return std::max(finite_or(v, 0.0f), 0.0f); }
Rgb clamped(Rgb c, float hi) {
  for (int i = 0; i < 3; ++i) c[i] = std::clamp(finite_or(c[i], 0.0f), 0.0f, hi);
  return c;
}
Rgb non_negative(Rgb c) { return clamped(c, std::numeric_limits<float>::max()); }
// An index of refraction that is not positive means no interface (pbrt-v4 reads eta 0 as 1).
float ior(float eta) { return eta > 0.0f && std::isfinite(eta) ? eta : 1.0f; }

TrowbridgeReitz distribution(const PbrtMaterialDesc& d, const TexturedFloat& ur, const TexturedFloat& vr) {
  const float u = non_negative(ur.value), v = non_negative(vr.value);
  if (!d.remap_roughness) return TrowbridgeReitz(u, v);
  return TrowbridgeReitz(TrowbridgeReitz::roughness_to_alpha(u), TrowbridgeReitz::roughness_to_alpha(v));
}
TrowbridgeReitz distribution(const PbrtMaterialDesc& d) { return distribution(d, d.uroughness, d.vroughness); }

RgbComplexIor conductor_ior(const PbrtMaterialDesc& d) {
  if (d.conductor_by_reflectance) {
    // pbrt-v4: eta = 1 and k = 2 sqrt(r) / sqrt(1 - r), whose normal-incidence reflectance is exactly r.
    const Rgb r = clamped(d.conductor_reflectance.value, kMaxPbrtConductorReflectance);
    Rgb k;
    for (int i = 0; i < 3; ++i) k[i] = 2.0f * std::sqrt(r[i]) / std::sqrt(1.0f - r[i]);
    return {Rgb(1.0f), k};
  }
  return {non_negative(d.conductor_eta.value), non_negative(d.conductor_k.value)};
}

// A texture's |g| >= 1 is brought to this (the Henyey-Greenstein phase function is a delta at |g| = 1).
constexpr float kMaxTexturedG = 0.999f;
float asymmetry(float g) {
  if (!std::isfinite(g)) return 0.0f;
  return std::abs(g) < 1.0f ? g : std::copysign(kMaxTexturedG, g);
}

// The coat of index eta (the material's roughness) and the medium under it.
LayerStack layers(const PbrtMaterialDesc& d, float eta) {
  return LayerStack{RoughDielectric{eta, distribution(d)}, non_negative(d.thickness.value),
                    clamped(d.albedo.value, 1.0f), asymmetry(d.g.value), d.max_depth, d.n_samples};
}

}  // namespace

Material build_pbrt_material(const PbrtMaterialDesc& d) {
  Material out;
  switch (d.kind) {
    case PbrtMaterialKind::Diffuse:
      out.surface = Lambert{clamped(d.reflectance.value, 1.0f)};
      break;
    case PbrtMaterialKind::Conductor: {
      const TrowbridgeReitz tr = distribution(d);
      const RgbComplexIor ior = conductor_ior(d);
      if (tr.effectively_smooth())
        out.delta = Conductor{Rgb(1.0f), 1.0f, 0.0f, ior};
      else
        out.surface = RoughConductor{tr, ior};
      break;
    }
    case PbrtMaterialKind::Dielectric: {
      const TrowbridgeReitz tr = distribution(d);
      const float eta = ior(d.eta.value);
      // eta = 1 is no interface at all (pbrt treats it as a specular pass-through, rough or not).
      if (eta == 1.0f || tr.effectively_smooth())
        out.delta = Dielectric{eta};
      else
        out.surface = RoughDielectric{eta, tr};
      break;
    }
    case PbrtMaterialKind::CoatedDiffuse:
      out.surface = CoatedDiffuse{{layers(d, ior(d.eta.value)), Lambert{clamped(d.reflectance.value, 1.0f)}}};
      break;
    case PbrtMaterialKind::CoatedConductor: {
      const float eta = ior(d.eta.value);
      // The conductor lies under the coat: its index relative to the coat's (pbrt-v4 divides eta and k by it).
      const RgbComplexIor c = conductor_ior(d);
      const TrowbridgeReitz base = distribution(d, d.conductor_uroughness, d.conductor_vroughness);
      out.surface = CoatedConductor{{layers(d, eta), RoughConductor{base, {c.eta / eta, c.k / eta}}}};
      break;
    }
    case PbrtMaterialKind::DiffuseTransmission: {
      const float scale = non_negative(d.scale);
      // pbrt-v4 scales first, then clamps to [0, 1].
      out.surface = DiffuseTransmission{clamped(d.reflectance.value * scale, 1.0f),
                                        clamped(d.transmittance.value * scale, 1.0f)};
      break;
    }
    case PbrtMaterialKind::ThinDielectric:
      out.delta = ThinDielectric{ior(d.eta.value)};
      break;
    case PbrtMaterialKind::Interface:
      out.passes_through = true;
      out.delta = Dielectric{1.0f};
      break;
  }
  return out;
}

namespace {

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
  if (m.pbrt) {
    PbrtCheck(ctx, *m.pbrt).check();
    return build_pbrt_material(*m.pbrt);
  }
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
