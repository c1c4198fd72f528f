#include "scenes/pbrt/spectrum.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "scenes/pbrt/named_spectra.h"

namespace kiln {
namespace {

constexpr int kLambdaMin = 360, kLambdaMax = 830;  // nm, the CIE tables' range, integrated in 1 nm steps
constexpr int kLambdaCount = kLambdaMax - kLambdaMin + 1;
// Wien's displacement constant (nm K): a blackbody peaks at this / T.
constexpr double kWienNmKelvin = 2.8977721e6;
// The conductor fit: incidence angles spaced evenly in projected solid angle (cos^2 uniform), and the
// Levenberg-Marquardt iterations that solve it (two unknowns: converged long before).
constexpr int kFitAngles = 8;
constexpr int kFitIterations = 60;

// Planck's spectral radiance (arbitrary scale) at lambda nm.
double planck(double lambda_nm, double kelvin) {
  constexpr double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
  const double l = lambda_nm * 1e-9;
  return (2.0 * h * c * c) / (std::pow(l, 5) * (std::exp((h * c) / (l * kb * kelvin)) - 1.0));
}

PiecewiseSpectrum from_data(const NamedSpectrumData& d) {
  PiecewiseSpectrum s;
  s.values.assign(d.values.begin(), d.values.end());
  if (!d.lambda_nm.empty()) {
    s.lambda_nm.assign(d.lambda_nm.begin(), d.lambda_nm.end());
  } else {
    s.lambda_nm.resize(s.values.size());
    for (size_t i = 0; i < s.values.size(); ++i) s.lambda_nm[i] = d.first_nm + d.step_nm * float(i);
  }
  return s;
}

const NamedSpectrumData* find_named(std::string_view name) {
  for (const NamedSpectrumData& d : named_spectra_data())
    if (d.name == name) return &d;
  return nullptr;
}

// Double-precision XYZ and RGB for the integrals (so that D65 reduces to exactly RGB 1).
struct Xyz {
  double x = 0, y = 0, z = 0;
};
std::array<double, 3> xyz_to_srgb(const Xyz& c) {
  return {3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z, -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z,
          0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z};
}

// The colour-matching functions on the integration grid, and the same weighted by D65 (pbrt's white).
struct Observer {
  std::array<Vec3f, kLambdaCount> cmf;
  std::array<Vec3f, kLambdaCount> cmf_d65;
  std::array<double, 3> d65_white;      // RGB of XYZ(D65) at Y = 1
  std::array<double, 3> d65_lit_white;  // RGB of the D65-weighted integral of a constant 1
};

// Integral of f(lambda) against the weights on the 1 nm grid.
template <typename F>
Xyz integrate(const std::array<Vec3f, kLambdaCount>& weights, F&& f) {
  Xyz r;
  for (int i = 0; i < kLambdaCount; ++i) {
    const double s = f(float(kLambdaMin + i));
    r.x += s * weights[size_t(i)].x;
    r.y += s * weights[size_t(i)].y;
    r.z += s * weights[size_t(i)].z;
  }
  return r;
}

Xyz normalised(Xyz c) { return {c.x / c.y, 1.0, c.z / c.y}; }

const Observer& observer() {
  static const Observer o = [] {
    Observer r;
    const PiecewiseSpectrum d65 = from_data(*find_named("stdillum-D65"));
    for (int i = 0; i < kLambdaCount; ++i) {
      const float l = float(kLambdaMin + i);
      r.cmf[size_t(i)] = cie_xyz_matching(l);
      r.cmf_d65[size_t(i)] = r.cmf[size_t(i)] * d65(l);
    }
    const Xyz white = integrate(r.cmf_d65, [](float) { return 1.0; });
    r.d65_white = xyz_to_srgb(normalised(white));
    r.d65_lit_white = xyz_to_srgb(white);
    return r;
  }();
  return o;
}

// Per-channel ratio of two RGB triples, negative channels clamped to 0, optionally scaled to luminance 1.
Rgb ratio(const std::array<double, 3>& a, const std::array<double, 3>& b, bool unit_luminance = false) {
  std::array<double, 3> r{};
  for (size_t c = 0; c < 3; ++c) r[c] = std::max(0.0, a[c] / b[c]);
  const double y = 0.2126 * r[0] + 0.7152 * r[1] + 0.0722 * r[2];
  const double scale = unit_luminance ? (y > 0.0 ? 1.0 / y : 0.0) : 1.0;
  return {float(r[0] * scale), float(r[1] * scale), float(r[2] * scale)};
}

template <typename F>
Rgb reduce(F&& f, SpectrumUse use) {
  const Observer& o = observer();
  if (use == SpectrumUse::Illuminant) {
    const Xyz xyz = integrate(o.cmf, f);
    if (!(xyz.y > 0.0)) return Rgb(0.0f);
    // Luminance 1 after the white point is made exact (the calibration moves it by up to ~0.5% for deep reds).
    return ratio(xyz_to_srgb(normalised(xyz)), o.d65_white, true);
  }
  return ratio(xyz_to_srgb(integrate(o.cmf_d65, f)), o.d65_lit_white);
}

// The conductor fit for one channel: (eta, k) whose Fresnel reflectance at cos_i[j] best matches target[j].
struct ChannelFit {
  std::array<float, kFitAngles> cos_i, target;

  float residual(float eta, float k, std::array<float, kFitAngles>* r = nullptr) const {
    float sum = 0.0f;
    for (int j = 0; j < kFitAngles; ++j) {
      const float d = fresnel_conductor(cos_i[size_t(j)], eta, k) - target[size_t(j)];
      if (r) (*r)[size_t(j)] = d;
      sum += d * d;
    }
    return sum;
  }

  // Levenberg-Marquardt in (log eta, k >= 0) from the separately reduced (eta, k).
  std::pair<float, float> solve(float eta, float k) const {
    float a = std::log(std::max(eta, 1e-3f)), b = std::max(k, 0.0f), lambda = 1e-3f;
    std::array<float, kFitAngles> r{}, ra{}, rb{};
    float err = residual(std::exp(a), b, &r);
    for (int it = 0; it < kFitIterations && err > 0.0f; ++it) {
      constexpr float h = 1e-3f;
      residual(std::exp(a + h), b, &ra);
      residual(std::exp(a), b + h, &rb);
      double jaa = 0, jab = 0, jbb = 0, ga = 0, gb = 0;
      for (size_t j = 0; j < kFitAngles; ++j) {
        const double da = (ra[j] - r[j]) / h, db = (rb[j] - r[j]) / h;
        jaa += da * da;
        jab += da * db;
        jbb += db * db;
        ga += da * r[j];
        gb += db * r[j];
      }
      const double maa = jaa * (1 + lambda), mbb = jbb * (1 + lambda), det = maa * mbb - jab * jab;
      if (!(std::abs(det) > 0.0)) break;
      const float na = a - float((mbb * ga - jab * gb) / det), nb = std::max(0.0f, b - float((maa * gb - jab * ga) / det));
      std::array<float, kFitAngles> nr{};
      const float nerr = residual(std::exp(na), nb, &nr);
      if (std::isfinite(nerr) && nerr < err) {
        a = na, b = nb, err = nerr, r = nr;
        lambda *= 0.3f;
      } else {
        lambda *= 10.0f;
      }
    }
    return {std::exp(a), b};
  }
};

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), size_t(0));
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

float PiecewiseSpectrum::operator()(float nm) const {
  if (lambda_nm.empty() || nm < lambda_nm.front() || nm > lambda_nm.back()) return 0.0f;
  const size_t i = size_t(std::upper_bound(lambda_nm.begin(), lambda_nm.end(), nm) - lambda_nm.begin());
  if (i == 0) return values.front();
  if (i >= lambda_nm.size()) return values.back();
  const float span = lambda_nm[i] - lambda_nm[i - 1];
  const float t = span > 0.0f ? (nm - lambda_nm[i - 1]) / span : 1.0f;
  return values[i - 1] + t * (values[i] - values[i - 1]);
}

Vec3f cie_xyz_matching(float l) {
  const CieObserverData cie = cie_1931_data();
  const float i = l - cie.first_nm;
  if (!(i >= 0.0f) || !(i <= float(cie.y.size() - 1))) return {0.0f, 0.0f, 0.0f};
  const size_t j = std::min(size_t(i), cie.y.size() - 2);
  const float t = i - float(j);
  const auto at = [&](std::span<const float> f) { return f[j] + t * (f[j + 1] - f[j]); };
  return {at(cie.x), at(cie.y), at(cie.z)};
}

Rgb xyz_to_linear_srgb(Vec3f c) {
  return {3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
          -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
          0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z};
}

Rgb chromaticity_to_linear_srgb(float x, float y) { return xyz_to_linear_srgb({x / y, 1.0f, (1.0f - x - y) / y}); }

Rgb spectrum_rgb(const PiecewiseSpectrum& s, SpectrumUse use) {
  if (use != SpectrumUse::Unbounded || s.lambda_nm.empty()) return reduce(s, use);
  // An index of refraction does not drop to 0 outside its table: its end values hold there.
  return reduce([&](float l) { return s(std::clamp(l, s.lambda_nm.front(), s.lambda_nm.back())); }, use);
}

Rgb sampled_spectrum_rgb(std::span<const float> lambda, std::span<const float> values, SpectrumUse use) {
  return spectrum_rgb(PiecewiseSpectrum{{lambda.begin(), lambda.end()}, {values.begin(), values.end()}}, use);
}

std::optional<PiecewiseSpectrum> blackbody_spectrum(float kelvin) {
  if (!(kelvin > 0.0f) || !std::isfinite(kelvin)) return std::nullopt;
  const double peak = planck(kWienNmKelvin / kelvin, kelvin);
  if (!(peak > 0.0) || !std::isfinite(peak)) return std::nullopt;
  PiecewiseSpectrum s;
  for (int l = kLambdaMin; l <= kLambdaMax; ++l) {
    s.lambda_nm.push_back(float(l));
    s.values.push_back(float(planck(l, kelvin) / peak));
  }
  return s;
}

Vec3f blackbody_xyz(float kelvin) {
  const Xyz xyz = normalised(integrate(observer().cmf, [&](float l) { return planck(l, kelvin); }));
  return {float(xyz.x), 1.0f, float(xyz.z)};
}

std::optional<Rgb> blackbody_rgb(float kelvin, SpectrumUse use) {
  const std::optional<PiecewiseSpectrum> s = blackbody_spectrum(kelvin);
  if (!s) return std::nullopt;
  const Rgb c = spectrum_rgb(*s, use);
  if (!c.is_finite()) return std::nullopt;
  return c;
}

std::optional<PiecewiseSpectrum> named_spectrum(std::string_view name) {
  const NamedSpectrumData* d = find_named(name);
  if (!d) return std::nullopt;
  return from_data(*d);
}

std::optional<Rgb> named_spectrum_rgb(std::string_view name, SpectrumUse use) {
  const std::optional<PiecewiseSpectrum> s = named_spectrum(name);
  if (!s) return std::nullopt;
  return spectrum_rgb(*s, use);
}

std::vector<std::string> nearest_named_spectra(std::string_view name, size_t count) {
  std::vector<std::pair<size_t, std::string_view>> scored;
  for (const NamedSpectrumData& d : named_spectra_data()) scored.emplace_back(edit_distance(name, d.name), d.name);
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (size_t i = 0; i < std::min(count, scored.size()); ++i) out.emplace_back(scored[i].second);
  return out;
}

RgbComplexIor conductor_rgb_ior(const PiecewiseSpectrum& eta, const PiecewiseSpectrum& k) {
  const Rgb eta_rgb = spectrum_rgb(eta, SpectrumUse::Unbounded), k_rgb = spectrum_rgb(k, SpectrumUse::Unbounded);
  std::array<ChannelFit, 3> fits{};
  for (int j = 0; j < kFitAngles; ++j) {
    const float cos_i = std::sqrt((float(j) + 0.5f) / float(kFitAngles));
    const Rgb target = reduce([&](float l) { return fresnel_conductor(cos_i, eta(l), k(l)); }, SpectrumUse::Albedo);
    for (int c = 0; c < 3; ++c) {
      fits[size_t(c)].cos_i[size_t(j)] = cos_i;
      fits[size_t(c)].target[size_t(j)] = target[c];
    }
  }
  RgbComplexIor out{eta_rgb, k_rgb};
  for (int c = 0; c < 3; ++c) {
    const ChannelFit& f = fits[size_t(c)];
    const auto [e, kk] = f.solve(eta_rgb[c], k_rgb[c]);
    // Keep the separate reduction should the fit not improve on it (it always does for pbrt's metals).
    if (f.residual(e, kk) < f.residual(eta_rgb[c], k_rgb[c])) {
      out.eta[c] = e;
      out.k[c] = kk;
    }
  }
  return out;
}

std::optional<RgbComplexIor> named_conductor_ior(std::string_view metal) {
  const std::string base = "metal-" + std::string(metal);
  const std::optional<PiecewiseSpectrum> eta = named_spectrum(base + "-eta"), k = named_spectrum(base + "-k");
  if (!eta || !k) return std::nullopt;
  return conductor_rgb_ior(*eta, *k);
}

}  // namespace kiln
