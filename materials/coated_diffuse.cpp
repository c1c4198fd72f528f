#include "materials/coated_diffuse.h"

#include <bit>
#include <initializer_list>

#include "core/rng.h"
#include "core/sampling.h"
#include "materials/fresnel.h"
#include "materials/henyey_greenstein.h"

namespace kiln {
namespace {

// Share of the uniform hemisphere in the pdf estimate (pbrt-v4 mixes 10% of a uniform density into its estimate,
// which keeps the pdf positive wherever the walk can exit).
constexpr float kUniformPdfShare = 0.1f;
// Russian roulette inside the walks (pbrt-v4's constants): after this many events, a throughput below the
// threshold survives with probability equal to it.
constexpr int kRouletteMinDepth = 3;
constexpr float kRouletteThreshold = 0.25f;
// Salts keep the eval, pdf and sample streams of the same directions apart.
constexpr uint64_t kEvalSalt = 0x6576616cull;    // "eval"
constexpr uint64_t kPdfSalt = 0x706466ull;       // "pdf"
constexpr uint64_t kSampleSalt = 0x73616d70ull;  // "samp"

uint64_t hash_floats(uint64_t salt, std::initializer_list<float> values) {
  uint64_t h = mix64(salt);
  for (float v : values) h = mix64(h ^ std::bit_cast<uint32_t>(v));
  return h;
}

Rng rng_for(uint64_t salt, Vec3f a, std::initializer_list<float> b) {
  return Rng(hash_floats(salt, {a.x, a.y, a.z}), hash_floats(salt + 1, b));
}

// Transmittance of the layer's medium (sigma_t = 1) over a vertical distance dz along w.
float transmittance(float dz, Vec3f w) {
  if (std::abs(dz) <= std::numeric_limits<float>::min()) return 1.0f;
  return std::exp(-std::abs(dz / w.z));
}

// Distance to the next scattering event in the medium, projected on z (exponential with rate 1 / |w.z|).
float sample_vertical_distance(float u, Vec3f w) { return -std::log1p(-u) * std::abs(w.z); }

bool usable(const std::optional<BsdfSample>& s) {
  return s && !s->f.is_black() && s->pdf > 0.0f && s->wi.z != 0.0f;
}

struct Walk {
  const CoatedDiffuse& m;
  // Density with which NEE through the coat (sampled from wi) produces the inside direction -w_up, the
  // competitor of a walk direction w_up heading for the coat (see the header's "Exit weights").
  float exit_nee_pdf(Vec3f w_up, Vec3f wi) const {
    if (m.exit_weight == LayeredExitWeight::PbrtV4) return m.coat.pdf(-w_up, wi, Transport::Radiance, kLobeTransmission);
    return m.coat.pdf(wi, -w_up, Transport::Importance, kLobeTransmission);
  }
  Rng& rng;
  float next() { return rng.next_float(); }
  Vec2f next_2d() { return rng.next_2d(); }
  float layer() const { return std::max(m.thickness, std::numeric_limits<float>::min()); }
  bool coat_specular() const { return m.coat.is_specular(); }
  bool has_medium() const { return !m.albedo.is_black(); }
};

}  // namespace

uint32_t CoatedDiffuse::flags() const {
  return kLobeReflection | kLobeDiffuse | (coat.is_specular() ? kLobeSpecular : kLobeGlossy);
}

float CoatedDiffuse::albedo_estimate() const {
  const float r = fresnel_dielectric(1.0f, coat.eta);
  return r + (1.0f - r) * reflectance.average();
}

// One estimate of f(wo, wi) per random walk, with next event estimation towards wi through the coat at every
// base and medium vertex (pbrt-v4's LayeredBxDF::f, specialised to a coat on top of a reflecting base: the walk
// always enters and leaves through the coat; exit MIS weights as the header explains).
Rgb CoatedDiffuse::eval(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return Rgb(0.0f);
  const int n = std::max(1, n_samples);
  Rng rng = rng_for(kEvalSalt, wo, {wi.x, wi.y, wi.z});
  Walk walk{*this, rng};
  const float t = walk.layer();
  const bool smooth = walk.coat_specular();
  const HenyeyGreenstein phase{g};
  Rgb f(float(n) * coat.f(wo, wi));  // the coat's own (rough) reflection, exact

  for (int s = 0; s < n; ++s) {
    // Enter through the coat along wos; the virtual light path leaves it along wis (adjoint transport).
    float uc = walk.next();
    const std::optional<BsdfSample> wos = coat.sample(wo, uc, walk.next_2d(), Transport::Radiance, kLobeTransmission);
    if (!usable(wos)) continue;
    uc = walk.next();
    const std::optional<BsdfSample> wis = coat.sample(wi, uc, walk.next_2d(), Transport::Importance, kLobeTransmission);
    if (!usable(wis)) continue;
    const Rgb wis_weight = wis->f / wis->pdf;

    Rgb beta = wos->f * (std::abs(wos->wi.z) / wos->pdf);
    float z = t;
    Vec3f w = wos->wi;
    for (int depth = 0; depth < max_depth; ++depth) {
      if (depth > kRouletteMinDepth && beta.max_component() < kRouletteThreshold) {
        const float q = std::max(0.0f, 1.0f - beta.max_component());
        if (walk.next() < q) break;
        beta *= 1.0f / (1.0f - q);
      }
      if (!walk.has_medium()) {
        z = (z == t) ? 0.0f : t;
        beta *= transmittance(t, w);
      } else {
        const float zp = w.z > 0.0f ? z + sample_vertical_distance(walk.next(), w) : z - sample_vertical_distance(walk.next(), w);
        if (zp == z) continue;
        if (0.0f < zp && zp < t) {
          // Scattering in the medium: NEE along wis, then continue along a phase-function sample.
          const float wt_nee = smooth ? 1.0f : power_heuristic(wis->pdf, phase.pdf(-w, -wis->wi));
          f += beta * albedo * wis_weight * (phase.p(-w, -wis->wi) * wt_nee * transmittance(zp - t, wis->wi));
          const std::optional<PhaseSample> ps = phase.sample(-w, walk.next_2d());
          if (!ps || ps->pdf == 0.0f || ps->wi.z == 0.0f) continue;
          beta *= albedo * (ps->p / ps->pdf);
          w = ps->wi;
          z = zp;
          // The phase sample heads for the coat: add its exit through the rough coat towards wi (MIS with NEE).
          if (w.z > 0.0f && !smooth) {
            const float f_exit = coat.f(-w, wi);
            if (f_exit > 0.0f) {
              const float wt = power_heuristic(ps->pdf, walk.exit_nee_pdf(w, wi));
              f += beta * (transmittance(zp - t, ps->wi) * f_exit * wt);
            }
          }
          continue;
        }
        z = std::clamp(zp, 0.0f, t);
      }

      if (z == t) {
        // At the coat from below: internal reflection only (leaving is accounted for by the NEE terms).
        uc = walk.next();
        const std::optional<BsdfSample> bs = coat.sample(-w, uc, walk.next_2d(), Transport::Radiance, kLobeReflection);
        if (!usable(bs)) break;
        beta *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
        w = bs->wi;
      } else {
        // At the diffuse base: NEE along wis, then a cosine-sampled bounce.
        const float base_pdf_nee = cosine_hemisphere_pdf(std::abs(wis->wi.z));
        const float wt_nee = smooth ? 1.0f : power_heuristic(wis->pdf, base_pdf_nee);
        f += beta * reflectance * wis_weight *
             (kInvPi * std::abs(wis->wi.z) * wt_nee * transmittance(t, wis->wi));
        const Vec3f wb = sample_cosine_hemisphere(walk.next_2d());
        const float base_pdf = cosine_hemisphere_pdf(wb.z);
        if (!(base_pdf > 0.0f)) break;
        beta *= reflectance;  // (R / pi) cos / (cos / pi)
        w = wb;
        if (!smooth) {
          const float f_exit = coat.f(-w, wi);
          if (f_exit > 0.0f) {
            const float wt = power_heuristic(base_pdf, walk.exit_nee_pdf(w, wi));
            f += beta * (transmittance(t, w) * f_exit * wt);
          }
        }
      }
    }
  }
  return f * (1.0f / float(n));
}

// pbrt-v4's pdf estimate: the coat's reflection pdf plus, per sample, the single internal bounce (transmit, reflect
// off the base, transmit) estimated with MIS, mixed with a uniform density.
float CoatedDiffuse::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
  const int n = std::max(1, n_samples);
  Rng rng = rng_for(kPdfSalt, wo, {wi.x, wi.y, wi.z});
  Walk walk{*this, rng};
  const bool smooth = walk.coat_specular();
  float sum = float(n) * coat.pdf(wo, wi, Transport::Radiance, kLobeReflection);
  for (int s = 0; s < n; ++s) {
    float uc = walk.next();
    const std::optional<BsdfSample> wos = coat.sample(wo, uc, walk.next_2d(), Transport::Radiance, kLobeTransmission);
    uc = walk.next();
    const std::optional<BsdfSample> wis = coat.sample(wi, uc, walk.next_2d(), Transport::Importance, kLobeTransmission);
    if (!usable(wos) || !usable(wis)) continue;
    const float base_pdf = cosine_hemisphere_pdf(std::abs(wis->wi.z));
    if (smooth) {
      sum += base_pdf;
      continue;
    }
    const Vec3f wr = sample_cosine_hemisphere(walk.next_2d());
    const float wr_pdf = cosine_hemisphere_pdf(wr.z);
    if (!(wr_pdf > 0.0f)) continue;
    sum += power_heuristic(wis->pdf, base_pdf) * base_pdf;
    const float exit_pdf = coat.pdf(-wr, wi);
    sum += power_heuristic(wr_pdf, exit_pdf) * exit_pdf;
  }
  return kUniformPdfShare * kInv2Pi + (1.0f - kUniformPdfShare) * sum / float(n);
}

// pbrt-v4's LayeredBxDF::Sample_f: a random walk that starts with a coat sample and ends when the walk transmits
// out through the coat (or is absorbed, truncated or rouletted: no sample).
std::optional<BsdfSample> CoatedDiffuse::sample(Vec3f wo, float uc, Vec2f u) const {
  if (!(wo.z > 0.0f)) return std::nullopt;
  const std::optional<BsdfSample> first = coat.sample(wo, uc, u);
  if (!usable(first)) return std::nullopt;
  // Path weight f |cos| / pdf re-expressed with the deterministic pdf estimate (see the header).
  auto with_estimated_pdf = [&](Vec3f wi, Rgb weight) -> std::optional<BsdfSample> {
    const float p = pdf(wo, wi);
    if (!(p > 0.0f) || !weight.is_finite()) return std::nullopt;
    return BsdfSample{weight * (p / std::abs(wi.z)), wi, p, kLobeReflection | kLobeGlossy};
  };
  if (!first->is_transmission()) {
    if (first->is_specular()) return first;  // the smooth coat's mirror reflection
    return with_estimated_pdf(first->wi, first->f * (std::abs(first->wi.z) / first->pdf));
  }

  Rng rng = rng_for(kSampleSalt, wo, {uc, u.x, u.y});
  Walk walk{*this, rng};
  const float t = walk.layer();
  const HenyeyGreenstein phase{g};
  Rgb f = first->f * std::abs(first->wi.z);
  float pdf_path = first->pdf;
  float z = t;
  Vec3f w = first->wi;
  for (int depth = 0; depth < max_depth; ++depth) {
    const float rr_beta = f.max_component() / pdf_path;
    if (depth > kRouletteMinDepth && rr_beta < kRouletteThreshold) {
      const float q = std::max(0.0f, 1.0f - rr_beta);
      if (walk.next() < q) return std::nullopt;
      pdf_path *= 1.0f - q;
    }
    if (w.z == 0.0f) return std::nullopt;
    if (walk.has_medium()) {
      const float dz = sample_vertical_distance(walk.next(), w);
      const float zp = w.z > 0.0f ? z + dz : z - dz;
      if (zp == z) return std::nullopt;
      if (0.0f < zp && zp < t) {
        const std::optional<PhaseSample> ps = phase.sample(-w, walk.next_2d());
        if (!ps || ps->pdf == 0.0f || ps->wi.z == 0.0f) return std::nullopt;
        f *= albedo * ps->p;
        pdf_path *= ps->pdf;
        w = ps->wi;
        z = zp;
        continue;
      }
      z = std::clamp(zp, 0.0f, t);
    } else {
      z = (z == t) ? 0.0f : t;
      f *= transmittance(t, w);
    }

    if (z == 0.0f) {
      const Vec3f wb = sample_cosine_hemisphere(walk.next_2d());
      const float base_pdf = cosine_hemisphere_pdf(wb.z);
      if (!(base_pdf > 0.0f)) return std::nullopt;
      f *= reflectance * (kInvPi * wb.z);
      pdf_path *= base_pdf;
      w = wb;
      continue;
    }
    const float uc2 = walk.next();
    const std::optional<BsdfSample> bs = coat.sample(-w, uc2, walk.next_2d());
    if (!usable(bs)) return std::nullopt;
    f *= bs->f;
    pdf_path *= bs->pdf;
    w = bs->wi;
    if (bs->is_transmission()) return with_estimated_pdf(w, f * (std::abs(w.z) / pdf_path));
    f *= std::abs(w.z);
  }
  return std::nullopt;
}

}  // namespace kiln
