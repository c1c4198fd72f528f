#include "scenes/pbrt/spectrum.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace kiln {
namespace {

constexpr float kLambdaMin = 360.0f, kLambdaMax = 830.0f;  // nm, the CIE tables' range
constexpr int kLambdaSteps = 470;                          // 1 nm
// Wavelengths at which unbounded spectra (indices of refraction) are read for R, G and B.
constexpr std::array<float, 3> kRgbWavelengths = {630.0f, 532.0f, 465.0f};

// One lobe of the fit: a Gaussian with different widths left and right of its centre.
float lobe(float lambda, float mu, float sigma_left, float sigma_right) {
  const float t = (lambda - mu) / (lambda < mu ? sigma_left : sigma_right);
  return std::exp(-0.5f * t * t);
}

// Planck's spectral radiance (arbitrary scale) at lambda nm.
double planck(double lambda_nm, double kelvin) {
  constexpr double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
  const double l = lambda_nm * 1e-9;
  return (2.0 * h * c * c) / (std::pow(l, 5) * (std::exp((h * c) / (l * kb * kelvin)) - 1.0));
}

template <typename F>
Vec3f integrate_xyz(F&& spectrum) {
  double x = 0, y = 0, z = 0;
  for (int i = 0; i <= kLambdaSteps; ++i) {
    const float l = kLambdaMin + (kLambdaMax - kLambdaMin) * float(i) / float(kLambdaSteps);
    const double s = spectrum(l);
    const Vec3f m = cie_xyz_matching(l);
    x += s * m.x;
    y += s * m.y;
    z += s * m.z;
  }
  return {float(x), float(y), float(z)};
}

float eval_piecewise_linear(std::span<const float> lambda, std::span<const float> values, float l) {
  if (lambda.empty() || l < lambda.front() || l > lambda.back()) return 0.0f;
  if (lambda.size() == 1) return values[0];
  size_t i = 1;
  while (i + 1 < lambda.size() && lambda[i] < l) ++i;
  const float span = lambda[i] - lambda[i - 1];
  const float t = span > 0.0f ? (l - lambda[i - 1]) / span : 1.0f;
  return values[i - 1] + t * (values[i] - values[i - 1]);
}

struct NamedRgb {
  std::string_view name;
  Rgb rgb;
};

// RGB reductions of measured metal optical constants, as used by RGB renderers for pbrt's named metals.
constexpr std::array<NamedRgb, 10> kMetals = {{
    {"metal-Ag-eta", {0.155265f, 0.116723f, 0.138342f}},
    {"metal-Ag-k", {4.82835f, 3.12225f, 2.14696f}},
    {"metal-Al-eta", {1.65746f, 0.880369f, 0.521229f}},
    {"metal-Al-k", {9.22387f, 6.26952f, 4.837f}},
    {"metal-Au-eta", {0.143119f, 0.374957f, 1.44248f}},
    {"metal-Au-k", {3.98316f, 2.38572f, 1.60322f}},
    {"metal-Cu-eta", {0.200438f, 0.924033f, 1.10221f}},
    {"metal-Cu-k", {3.91295f, 2.45285f, 2.14219f}},
    {"metal-CuZn-eta", {0.444f, 0.527f, 1.094f}},
    {"metal-CuZn-k", {3.695f, 2.765f, 1.829f}},
}};

struct NamedIor {
  std::string_view name;
  float n_d;
};
// Catalogue refractive indices n_d (587.6 nm) of the glasses pbrt names.
constexpr std::array<NamedIor, 5> kGlasses = {{
    {"glass-BK7", 1.5168f},
    {"glass-BAF10", 1.6700f},
    {"glass-FK51A", 1.4866f},
    {"glass-LASF9", 1.8503f},
    {"glass-F5", 1.6034f},
}};

}  // namespace

Vec3f cie_xyz_matching(float l) {
  const float x = 1.056f * lobe(l, 599.8f, 37.9f, 31.0f) + 0.362f * lobe(l, 442.0f, 16.0f, 26.7f) -
                  0.065f * lobe(l, 501.1f, 20.4f, 26.2f);
  const float y = 0.821f * lobe(l, 568.8f, 46.9f, 40.5f) + 0.286f * lobe(l, 530.9f, 16.3f, 31.1f);
  const float z = 1.217f * lobe(l, 437.0f, 11.8f, 36.0f) + 0.681f * lobe(l, 459.0f, 26.0f, 13.8f);
  return {x, y, z};
}

Rgb xyz_to_linear_srgb(Vec3f c) {
  return {3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
          -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
          0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z};
}

Rgb chromaticity_to_linear_srgb(float x, float y) { return xyz_to_linear_srgb({x / y, 1.0f, (1.0f - x - y) / y}); }

Vec3f blackbody_xyz(float kelvin) {
  const Vec3f xyz = integrate_xyz([&](float l) { return planck(l, kelvin); });
  return xyz / xyz.y;
}

std::optional<Rgb> blackbody_rgb(float kelvin) {
  if (!(kelvin > 0.0f) || !std::isfinite(kelvin)) return std::nullopt;
  const Vec3f xyz = blackbody_xyz(kelvin);
  if (!is_finite(xyz)) return std::nullopt;
  return xyz_to_linear_srgb(xyz);
}

Rgb sampled_spectrum_rgb(std::span<const float> lambda, std::span<const float> values, SpectrumUse use) {
  if (use == SpectrumUse::Unbounded) {
    Rgb out;
    for (int c = 0; c < 3; ++c) {
      // Outside the given range the nearest end value holds (an IOR does not drop to 0).
      const float l = std::clamp(kRgbWavelengths[size_t(c)], lambda.front(), lambda.back());
      out[c] = eval_piecewise_linear(lambda, values, l);
    }
    return out;
  }
  const Vec3f xyz = integrate_xyz([&](float l) { return eval_piecewise_linear(lambda, values, l); });
  if (use == SpectrumUse::Illuminant) return xyz.y > 0.0f ? xyz_to_linear_srgb(xyz / xyz.y) : Rgb(0.0f);
  const Rgb white = xyz_to_linear_srgb(integrate_xyz([](float) { return 1.0f; }));
  return xyz_to_linear_srgb(xyz) / white;
}

std::optional<Rgb> named_spectrum_rgb(std::string_view name, SpectrumUse) {
  if (name == "stdillum-D65") return Rgb(1.0f);
  if (name == "stdillum-D50") return chromaticity_to_linear_srgb(0.34567f, 0.35850f);
  if (name == "stdillum-A") return chromaticity_to_linear_srgb(0.44757f, 0.40745f);
  if (name == "illum-acesD60") return chromaticity_to_linear_srgb(0.32168f, 0.33767f);
  for (const NamedRgb& m : kMetals)
    if (m.name == name) return m.rgb;
  for (const NamedIor& g : kGlasses)
    if (g.name == name) return Rgb(g.n_d);
  return std::nullopt;
}

}  // namespace kiln
