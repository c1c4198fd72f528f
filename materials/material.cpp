// Material = optional surface BRDF + optional delta BSDF.
//
// Sidedness: surface BRDFs are written for wo.z > 0; the material makes them two-sided by mirroring both
// directions through the surface plane when wo.z < 0 (so a dielectric's glossy coat also works from inside).
// Surface BSDFs with kHandlesBothSides (RoughDielectric) and delta parts handle both sides themselves (the
// dielectric needs the side to know which way it refracts).
//
// Lobe choice in sample(): the delta part is picked with probability
//   delta_probability(wo) = a_delta / (a_surface + a_delta)
// where a_surface is the surface BRDF's normal-incidence albedo estimate and a_delta is the mirror colour
// average (mirror), mirror colour times conductor Fresnel at wo (conductor) or 1 (dielectric). It is 1 with no
// surface, 0 with no delta part and 1/2 when both estimates vanish. pdf() includes the factor 1 - that.
#include "materials/material.h"

namespace kiln {
namespace {

Vec3f flip_z(Vec3f w) { return {w.x, w.y, -w.z}; }

template <class B>
constexpr bool handles_both_sides() {
  if constexpr (requires { B::kHandlesBothSides; })
    return B::kHandlesBothSides;
  else
    return false;
}

template <class B>
constexpr bool ignores_lobe_choice() {
  if constexpr (requires { B::kIgnoresLobeChoice; })
    return B::kIgnoresLobeChoice;
  else
    return std::is_same_v<B, NoSurface>;
}

float clamp_unit(float u) { return std::clamp(u, 0.0f, kOneMinusEpsilon); }

float surface_albedo_estimate(const SurfaceBrdf& s) {
  return std::visit(
      [](const auto& b) -> float {
        if constexpr (std::is_same_v<std::decay_t<decltype(b)>, NoSurface>)
          return 0.0f;
        else
          return b.albedo_estimate();
      },
      s);
}

float delta_albedo_estimate(const DeltaBsdf& d, Vec3f wo) {
  return std::visit(
      [wo](const auto& b) -> float {
        if constexpr (std::is_same_v<std::decay_t<decltype(b)>, NoDelta>)
          return 0.0f;
        else
          return b.albedo_estimate(wo);
      },
      d);
}

int delta_branches_of(const DeltaBsdf& d, Vec3f wo, SpecularBranch out[2]) {
  return std::visit(
      [&](const auto& b) -> int {
        if constexpr (std::is_same_v<std::decay_t<decltype(b)>, NoDelta>)
          return 0;
        else
          return b.branches(wo, out);
      },
      d);
}

// Surface BSDF for wo on either side: mirrored into +z unless the BSDF handles both sides itself.
Rgb surface_eval(const SurfaceBrdf& s, Vec3f wo, Vec3f wi) {
  return std::visit(
      [&](const auto& b) -> Rgb {
        using B = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<B, NoSurface>)
          return Rgb(0.0f);
        else if constexpr (handles_both_sides<B>())
          return b.eval(wo, wi);
        else
          return wo.z < 0.0f ? b.eval(flip_z(wo), flip_z(wi)) : b.eval(wo, wi);
      },
      s);
}

float surface_pdf(const SurfaceBrdf& s, Vec3f wo, Vec3f wi) {
  return std::visit(
      [&](const auto& b) -> float {
        using B = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<B, NoSurface>)
          return 0.0f;
        else if constexpr (handles_both_sides<B>())
          return b.pdf(wo, wi);
        else
          return wo.z < 0.0f ? b.pdf(flip_z(wo), flip_z(wi)) : b.pdf(wo, wi);
      },
      s);
}

std::optional<BsdfSample> surface_sample(const SurfaceBrdf& s, Vec3f wo, float uc, Vec2f u) {
  return std::visit(
      [&](const auto& b) -> std::optional<BsdfSample> {
        using B = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<B, NoSurface>) {
          return std::nullopt;
        } else if constexpr (handles_both_sides<B>()) {
          return b.sample(wo, uc, u);
        } else {
          if (!(wo.z < 0.0f)) return b.sample(wo, uc, u);
          std::optional<BsdfSample> bs = b.sample(flip_z(wo), uc, u);
          if (bs) bs->wi = flip_z(bs->wi);
          return bs;
        }
      },
      s);
}

bool surface_handles_both_sides(const SurfaceBrdf& s) {
  return std::visit([](const auto& b) { return handles_both_sides<std::decay_t<decltype(b)>>(); }, s);
}

uint32_t surface_part_flags(const SurfaceBrdf& s) {
  return std::visit(
      [](const auto& b) -> uint32_t {
        if constexpr (std::is_same_v<std::decay_t<decltype(b)>, NoSurface>)
          return kLobeNone;
        else
          return b.flags();
      },
      s);
}

uint32_t delta_flags(const DeltaBsdf& d) {
  return std::visit(
      [](const auto& b) -> uint32_t {
        if constexpr (std::is_same_v<std::decay_t<decltype(b)>, NoDelta>)
          return kLobeNone;
        else
          return b.flags();
      },
      d);
}

bool valid_sample(const BsdfSample& s) {
  return s.pdf > 0.0f && std::isfinite(s.pdf) && s.f.is_finite() && !s.f.has_negative() && is_finite(s.wi);
}

}  // namespace

uint32_t Material::flags() const { return surface_part_flags(surface) | delta_flags(delta); }

uint32_t Material::surface_flags() const { return surface_part_flags(surface); }

bool Material::reads_lobe_choice() const {
  return has_delta() ||
         !std::visit([](const auto& b) { return ignores_lobe_choice<std::decay_t<decltype(b)>>(); }, surface);
}

bool Material::oriented() const {
  return std::holds_alternative<Dielectric>(delta) || surface_handles_both_sides(surface);
}

namespace {

const char* variant_suffix(PhongVariant v) {
  switch (v) {
    case PhongVariant::Original: return "(original)";
    case PhongVariant::Modified: return "(modified)";
    case PhongVariant::ModifiedNormalized: return "(normalized)";
  }
  return "";
}

std::string name_of(const NoSurface&) { return ""; }
std::string name_of(const Lambert&) { return "lambert"; }
std::string name_of(const Phong& b) { return std::string("phong") + variant_suffix(b.variant); }
std::string name_of(const BlinnPhong& b) { return std::string("blinn-phong") + variant_suffix(b.variant); }
std::string name_of(const TorranceSparrow&) { return "torrance-sparrow"; }
std::string name_of(const RoughConductor&) { return "rough-conductor"; }
std::string name_of(const RoughDielectric&) { return "rough-dielectric"; }
std::string name_of(const CoatedDiffuse&) { return "coated-diffuse"; }
std::string name_of(const CoatedConductor&) { return "coated-conductor"; }
std::string name_of(const DiffuseTransmission&) { return "diffuse-transmission"; }
std::string name_of(const NoDelta&) { return ""; }
std::string name_of(const Mirror&) { return "mirror"; }
std::string name_of(const Dielectric&) { return "dielectric"; }
std::string name_of(const Conductor&) { return "conductor"; }
std::string name_of(const ThinDielectric&) { return "thin-dielectric"; }

}  // namespace

std::string Material::describe() const {
  if (passes_through) return "interface";
  const std::string s = std::visit([](const auto& b) { return name_of(b); }, surface);
  std::string d = std::visit([](const auto& b) { return name_of(b); }, delta);
  if (!d.empty() && roughness > 0.0f) d = "rough-" + d;
  if (s.empty() && d.empty()) return "none";
  return s.empty() ? d : d.empty() ? s : s + "+" + d;
}

Rgb Material::eval(Vec3f wo, Vec3f wi) const {
  if (!has_surface()) return Rgb(0.0f);
  return surface_eval(surface, wo, wi);
}

float Material::delta_probability(Vec3f wo) const {
  if (!has_delta()) return 0.0f;
  if (!has_surface()) return 1.0f;
  const float a_s = std::max(0.0f, surface_albedo_estimate(surface));
  const float a_d = std::max(0.0f, delta_albedo_estimate(delta, wo));
  if (!(a_s + a_d > 0.0f)) return 0.5f;
  return a_d / (a_s + a_d);
}

float Material::pdf(Vec3f wo, Vec3f wi) const {
  if (!has_surface()) return 0.0f;
  return (1.0f - delta_probability(wo)) * surface_pdf(surface, wo, wi);
}

std::optional<BsdfSample> Material::sample_delta(Vec3f wo, float uc, Vec2f u) const {
  SpecularBranch b[2];
  const int n = delta_branches_of(delta, wo, b);
  if (n == 0) return std::nullopt;
  // Choose the branch first, then roughen only the chosen direction.
  int i = 0;
  float cdf = b[0].probability;
  while (i + 1 < n && uc >= cdf) cdf += b[++i].probability;
  SpecularBranch chosen = b[i];
  const std::optional<Vec3f> wi = perturb(chosen.wi, roughness, u);
  if (!wi) return std::nullopt;
  chosen.wi = *wi;
  std::optional<BsdfSample> s = sample_branch(&chosen, 1, 0.0f);
  if (!s || !valid_sample(*s)) return std::nullopt;
  return s;
}

std::optional<BsdfSample> Material::sample(Vec3f wo, float uc, Vec2f u) const {
  if (!is_finite(wo)) return std::nullopt;
  const float pd = delta_probability(wo);
  if (uc < pd) {
    std::optional<BsdfSample> s = sample_delta(wo, clamp_unit(uc / pd), u);
    if (!s) return std::nullopt;
    s->pdf *= pd;
    if (!valid_sample(*s)) return std::nullopt;
    return s;
  }
  if (!has_surface()) return std::nullopt;
  std::optional<BsdfSample> s = surface_sample(surface, wo, clamp_unit((uc - pd) / (1.0f - pd)), u);
  if (!s) return std::nullopt;
  s->pdf *= 1.0f - pd;
  if (!valid_sample(*s)) return std::nullopt;
  return s;
}

std::optional<BsdfSample> Material::sample_surface(Vec3f wo, float uc, Vec2f u) const {
  if (!is_finite(wo) || !has_surface()) return std::nullopt;
  std::optional<BsdfSample> s = surface_sample(surface, wo, clamp_unit(uc), u);
  if (!s || !valid_sample(*s)) return std::nullopt;
  return s;
}

float Material::pdf_surface(Vec3f wo, Vec3f wi) const {
  return has_surface() ? surface_pdf(surface, wo, wi) : 0.0f;
}

int Material::delta_branches(Vec3f wo, DeltaBranch out[2]) const {
  SpecularBranch b[2];
  const int n = delta_branches_of(delta, wo, b);
  for (int i = 0; i < n; ++i) out[i] = DeltaBranch{b[i].wi, b[i].weight, b[i].transmission, b[i].etap};
  return n;
}

}  // namespace kiln
