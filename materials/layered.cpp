#include "materials/layered.h"

#include <bit>
#include <initializer_list>
#include <type_traits>
#include <utility>

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

template <class B>
bool is_specular_bxdf(const B& b) {
  return (b.flags() & kLobeSpecular) != 0;
}

// A bounce off the base: direction, density, f |cos| and the path weight f |cos| / pdf.
struct BaseBounce {
  Vec3f wi;
  float pdf;
  Rgb f_cos;
  Rgb weight;
  bool specular;
};

// The random walk's state and the stack it walks through.
template <class Base>
struct Walk {
  const LayerStack& s;
  const Base& base;
  Rng& rng;

  float next() { return rng.next_float(); }
  Vec2f next_2d() { return rng.next_2d(); }
  float layer() const { return std::max(s.thickness, std::numeric_limits<float>::min()); }
  bool coat_specular() const { return s.coat.is_specular(); }
  bool base_specular() const { return is_specular_bxdf(base); }
  bool has_medium() const { return !s.albedo.is_black(); }
  std::optional<BsdfSample> sample_coat(Vec3f w, Transport mode, uint32_t lobes) {
    const float uc = next();
    return s.coat.sample(w, uc, next_2d(), mode, lobes);
  }
  // A bounce off the base from the inside direction w. The Lambertian base is sampled in closed form (cosine
  // weighted: weight = reflectance exactly, and no lobe choice to draw), other bases through their sample().
  std::optional<BaseBounce> bounce_base(Vec3f w) {
    if constexpr (std::is_same_v<Base, Lambert>) {
      const Vec3f wb = sample_cosine_hemisphere(next_2d());
      const float p = cosine_hemisphere_pdf(wb.z);
      if (!(p > 0.0f)) return std::nullopt;
      return BaseBounce{wb, p, base.reflectance * (kInvPi * wb.z), base.reflectance, false};
    } else {
      const float uc = next();
      const std::optional<BsdfSample> bs = base.sample(w, uc, next_2d());
      if (!usable(bs)) return std::nullopt;
      const float cos_i = std::abs(bs->wi.z);
      return BaseBounce{bs->wi, bs->pdf, bs->f * cos_i, bs->f * (cos_i / bs->pdf), bs->is_specular()};
    }
  }
  // The base's f(wo, wi) as a colour and a scale, Lambert's kept factored as reflectance and 1 / pi (the rounding
  // of its closed form).
  std::pair<Rgb, float> base_f(Vec3f wo, Vec3f wi) const {
    if constexpr (std::is_same_v<Base, Lambert>) return {base.reflectance, kInvPi};
    else return {base.eval(wo, wi), 1.0f};
  }
  // Density with which NEE through the coat (sampled from wi) produces the inside direction -w_up, the
  // competitor of a walk direction w_up heading for the coat (see the header's "Exit weights").
  float exit_nee_pdf(Vec3f w_up, Vec3f wi) const {
    if (s.exit_weight == LayeredExitWeight::PbrtV4)
      return s.coat.pdf(-w_up, wi, Transport::Radiance, kLobeTransmission);
    return s.coat.pdf(wi, -w_up, Transport::Importance, kLobeTransmission);
  }
  // The walk heads up along w from a vertex whose own sampling density of w is p_walk: its exit through the rough
  // coat towards wi, attenuated over the vertical distance dz to the coat (MIS with NEE).
  Rgb exit_towards(Vec3f w, Vec3f wi, float p_walk, float dz) const {
    const float f_exit = s.coat.f(-w, wi);
    if (!(f_exit > 0.0f)) return Rgb(0.0f);
    return Rgb(transmittance(dz, w) * f_exit * power_heuristic(p_walk, exit_nee_pdf(w, wi)));
  }
  // Russian roulette on a throughput estimate; false when the walk ends. `survive` receives the survival
  // probability the caller divides by.
  bool roulette(int depth, float throughput, float& survive) {
    survive = 1.0f;
    if (depth <= kRouletteMinDepth || throughput >= kRouletteThreshold) return true;
    const float q = std::max(0.0f, 1.0f - throughput);
    if (next() < q) return false;
    survive = 1.0f - q;
    return true;
  }
};

}  // namespace

template <class Base>
uint32_t Layered<Base>::flags() const {
  const uint32_t coat = layers.coat.flags(), bottom = base.flags();
  uint32_t f = kLobeReflection | ((coat | bottom) & kLobeGlossy);
  if (coat & kLobeSpecular) f |= kLobeSpecular;
  if ((bottom & kLobeDiffuse) || !layers.albedo.is_black()) f |= kLobeDiffuse;
  return f;
}

template <class Base>
float Layered<Base>::albedo_estimate() const {
  const float r = fresnel_dielectric(1.0f, layers.coat.eta);
  return r + (1.0f - r) * base.albedo_estimate();
}

// One estimate of f(wo, wi) per random walk, with next event estimation towards wi through the coat at every
// base and medium vertex (pbrt-v4's LayeredBxDF::f, specialised to a coat on top of a reflecting base: the walk
// always enters and leaves through the coat; exit MIS weights as the header explains).
template <class Base>
Rgb Layered<Base>::eval(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return Rgb(0.0f);
  const int n = std::max(1, layers.n_samples);
  Rng rng = rng_for(kEvalSalt, wo, {wi.x, wi.y, wi.z});
  Walk<Base> walk{layers, base, rng};
  const LayerStack& s = layers;
  const float t = walk.layer();
  const bool smooth = walk.coat_specular(), base_smooth = walk.base_specular();
  const HenyeyGreenstein phase{s.g};
  Rgb f(float(n) * s.coat.f(wo, wi));  // the coat's own (rough) reflection, exact

  for (int k = 0; k < n; ++k) {
    // Enter through the coat along wos; the virtual light path leaves it along wis (adjoint transport).
    const std::optional<BsdfSample> wos = walk.sample_coat(wo, Transport::Radiance, kLobeTransmission);
    if (!usable(wos)) continue;
    const std::optional<BsdfSample> wis = walk.sample_coat(wi, Transport::Importance, kLobeTransmission);
    if (!usable(wis)) continue;
    const Rgb wis_weight = wis->f / wis->pdf;

    Rgb beta = wos->f * (std::abs(wos->wi.z) / wos->pdf);
    float z = t;
    Vec3f w = wos->wi;
    for (int depth = 0; depth < s.max_depth; ++depth) {
      float survive = 1.0f;
      if (!walk.roulette(depth, beta.max_component(), survive)) break;
      beta *= 1.0f / survive;
      if (!walk.has_medium()) {
        z = (z == t) ? 0.0f : t;
        beta *= transmittance(t, w);
      } else {
        const float zp = w.z > 0.0f ? z + sample_vertical_distance(walk.next(), w) : z - sample_vertical_distance(walk.next(), w);
        if (zp == z) continue;
        if (0.0f < zp && zp < t) {
          // Scattering in the medium: NEE along wis, then continue along a phase-function sample.
          const float wt_nee = smooth ? 1.0f : power_heuristic(wis->pdf, phase.pdf(-w, -wis->wi));
          f += beta * s.albedo * wis_weight * (phase.p(-w, -wis->wi) * wt_nee * transmittance(zp - t, wis->wi));
          const std::optional<PhaseSample> ps = phase.sample(-w, walk.next_2d());
          if (!ps || ps->pdf == 0.0f || ps->wi.z == 0.0f) continue;
          beta *= s.albedo * (ps->p / ps->pdf);
          w = ps->wi;
          z = zp;
          if (w.z > 0.0f && !smooth) f += beta * walk.exit_towards(w, wi, ps->pdf, zp - t);
          continue;
        }
        z = std::clamp(zp, 0.0f, t);
      }

      if (z == t) {
        // At the coat from below: internal reflection only (leaving is accounted for by the NEE terms).
        const std::optional<BsdfSample> bs = walk.sample_coat(-w, Transport::Radiance, kLobeReflection);
        if (!usable(bs)) break;
        beta *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
        w = bs->wi;
        continue;
      }
      // At the base: NEE along wis (a smooth base has no direction to evaluate), then a sampled bounce.
      if (!base_smooth) {
        const float wt_nee = smooth ? 1.0f : power_heuristic(wis->pdf, base.pdf(-w, -wis->wi));
        const auto [f_base, scale] = walk.base_f(-w, -wis->wi);
        f += beta * f_base * wis_weight * (scale * std::abs(wis->wi.z) * wt_nee * transmittance(t, wis->wi));
      }
      const std::optional<BaseBounce> bs = walk.bounce_base(-w);
      if (!bs) break;
      beta *= bs->weight;
      w = bs->wi;
      if (smooth) continue;
      // The bounce heads for the rough coat: its exit towards wi. A smooth base's mirror direction has no
      // competing NEE strategy.
      f += beta * (base_smooth ? Rgb(transmittance(t, w) * s.coat.f(-w, wi)) : walk.exit_towards(w, wi, bs->pdf, t));
    }
  }
  return f * (1.0f / float(n));
}

// pbrt-v4's pdf estimate: the coat's reflection pdf plus, per sample, the single internal bounce (transmit, reflect
// off the base, transmit) estimated with MIS, mixed with a uniform density.
template <class Base>
float Layered<Base>::pdf(Vec3f wo, Vec3f wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
  const int n = std::max(1, layers.n_samples);
  Rng rng = rng_for(kPdfSalt, wo, {wi.x, wi.y, wi.z});
  Walk<Base> walk{layers, base, rng};
  const RoughDielectric& coat = layers.coat;
  const bool smooth = walk.coat_specular(), base_smooth = walk.base_specular();
  float sum = float(n) * coat.pdf(wo, wi, Transport::Radiance, kLobeReflection);
  for (int k = 0; k < n; ++k) {
    const std::optional<BsdfSample> wos = walk.sample_coat(wo, Transport::Radiance, kLobeTransmission);
    const std::optional<BsdfSample> wis = walk.sample_coat(wi, Transport::Importance, kLobeTransmission);
    if (!usable(wos) || !usable(wis)) continue;
    if (smooth) {
      sum += base.pdf(-wos->wi, -wis->wi);
      continue;
    }
    const std::optional<BaseBounce> rs = walk.bounce_base(-wos->wi);
    if (!rs) continue;
    const float exit_pdf = coat.pdf(-rs->wi, wi);
    if (base_smooth) {
      sum += exit_pdf;
      continue;
    }
    const float base_pdf = base.pdf(-wos->wi, -wis->wi);
    sum += power_heuristic(wis->pdf, base_pdf) * base_pdf;
    sum += power_heuristic(rs->pdf, exit_pdf) * exit_pdf;
  }
  return kUniformPdfShare * kInv2Pi + (1.0f - kUniformPdfShare) * sum / float(n);
}

// pbrt-v4's LayeredBxDF::Sample_f: a random walk that starts with a coat sample and ends when the walk transmits
// out through the coat (or is absorbed, truncated or rouletted: no sample). A walk made of specular events only
// leaves in a delta direction and is returned as a specular sample.
template <class Base>
std::optional<BsdfSample> Layered<Base>::sample(Vec3f wo, float uc, Vec2f u) const {
  if (!(wo.z > 0.0f)) return std::nullopt;
  const LayerStack& s = layers;
  const std::optional<BsdfSample> first = s.coat.sample(wo, uc, u);
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
  Walk<Base> walk{s, base, rng};
  const float t = walk.layer();
  const HenyeyGreenstein phase{s.g};
  Rgb f = first->f * std::abs(first->wi.z);
  float pdf_path = first->pdf;
  bool specular_path = first->is_specular();
  float z = t;
  Vec3f w = first->wi;
  for (int depth = 0; depth < s.max_depth; ++depth) {
    float survive = 1.0f;
    if (!walk.roulette(depth, f.max_component() / pdf_path, survive)) return std::nullopt;
    pdf_path *= survive;
    if (w.z == 0.0f) return std::nullopt;
    if (walk.has_medium()) {
      const float dz = sample_vertical_distance(walk.next(), w);
      const float zp = w.z > 0.0f ? z + dz : z - dz;
      if (zp == z) return std::nullopt;
      if (0.0f < zp && zp < t) {
        const std::optional<PhaseSample> ps = phase.sample(-w, walk.next_2d());
        if (!ps || ps->pdf == 0.0f || ps->wi.z == 0.0f) return std::nullopt;
        f *= s.albedo * ps->p;
        pdf_path *= ps->pdf;
        specular_path = false;
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
      const std::optional<BaseBounce> bs = walk.bounce_base(-w);
      if (!bs) return std::nullopt;
      f *= bs->f_cos;
      pdf_path *= bs->pdf;
      specular_path &= bs->specular;
      w = bs->wi;
      continue;
    }
    const std::optional<BsdfSample> bs = walk.sample_coat(-w, Transport::Radiance, kSampleAll);
    if (!usable(bs)) return std::nullopt;
    f *= bs->f;
    pdf_path *= bs->pdf;
    specular_path &= bs->is_specular();
    w = bs->wi;
    if (bs->is_transmission()) {
      if (specular_path) return BsdfSample{f / pdf_path, w, 1.0f, kLobeReflection | kLobeSpecular};
      return with_estimated_pdf(w, f * (std::abs(w.z) / pdf_path));
    }
    f *= std::abs(w.z);
  }
  return std::nullopt;
}

template struct Layered<Lambert>;
template struct Layered<RoughConductor>;

}  // namespace kiln
