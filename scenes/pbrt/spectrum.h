// pbrt-v4 spectra reduced to Kiln's linear RGB (Rec. 709 primaries, D65 white, like pbrt's default "srgb" colour
// space). pbrt renders spectrally; Kiln renders RGB, so every spectral parameter becomes one RGB triple here. The
// reduction is what pbrt's RGB film records for the spectrum in the simplest setting of its use:
//   * illuminants (light "L" / "I"): pbrt divides an emission spectrum by its luminance ("scale so that radiance
//     is equivalent to 1 nit"), so only its chromaticity survives: the RGB of the spectrum's XYZ at Y = 1, divided per
//     channel by the same for D65 (so stdillum-D65 is exactly RGB 1, as in pbrt, where D65 is the colour space's
//     white). An RGB illuminant is taken as written (pbrt multiplies it by the colour space's D65 illuminant and
//     divides by that illuminant's luminance, so "rgb L [1 1 1]" is RGB 1);
//   * reflectances (albedos) and other unbounded quantities (a dielectric's eta): the colour of the spectrum as a
//     reflectance lit by D65, i.e. the RGB of XYZ(s(lambda) D65(lambda)) divided per channel by the RGB of
//     XYZ(D65), so a constant c gives (c, c, c); channels that come out negative (spectra narrower than a primary)
//     are clamped to 0;
//   * a conductor's eta and k given as a pair of spectra (named, tabulated or from files; pbrt's default copper):
//     the per-channel (eta, k) whose Fresnel reflectance best matches, over the hemisphere, the reflectance the
//     spectral conductor shows as a reflectance lit by D65 (least squares over 8 incidence angles spaced evenly in
//     projected solid angle). Reducing eta and k separately instead makes gold's red up to 3% too dark.
// XYZ uses the tabulated CIE 1931 2-degree observer (the table pbrt-v4 integrates against), over 360-830 nm in
// 1 nm steps.
//
// Named spectra: every one pbrt-v4 ships (scenes/pbrt/named_spectra.h: glasses, metals, standard illuminants,
// camera sensor curves), from its tabulated data. Blackbodies: Planck's law normalised to a peak of 1, as pbrt-v4's
// BlackbodySpectrum (only the chromaticity matters for an illuminant).
#pragma once
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/color.h"
#include "core/vec.h"
#include "materials/fresnel.h"

namespace kiln {

enum class SpectrumUse { Illuminant, Albedo, Unbounded };

// A piecewise-linear spectrum: values at increasing wavelengths (nm), zero outside them (pbrt-v4's
// PiecewiseLinearSpectrum).
struct PiecewiseSpectrum {
  std::vector<float> lambda_nm, values;
  float operator()(float nm) const;
};

// CIE 1931 colour-matching functions (x-bar, y-bar, z-bar) at a wavelength in nanometres: the tabulated 2-degree
// observer (1 nm steps, linear between them, 0 outside 360-830 nm).
Vec3f cie_xyz_matching(float lambda_nm);
Rgb xyz_to_linear_srgb(Vec3f xyz);
// Chromaticity (x, y) at luminance 1 as linear sRGB.
Rgb chromaticity_to_linear_srgb(float x, float y);

// The reduction above.
Rgb spectrum_rgb(const PiecewiseSpectrum& s, SpectrumUse use);
// The same for (wavelength, value) pairs given as two arrays (at least one pair, wavelengths increasing).
Rgb sampled_spectrum_rgb(std::span<const float> lambda_nm, std::span<const float> values, SpectrumUse use);

// Planck's law at `kelvin`, normalised to a peak of 1; empty unless kelvin is positive and finite.
std::optional<PiecewiseSpectrum> blackbody_spectrum(float kelvin);
// A blackbody reduced for `use` (an illuminant: luminance 1); empty unless kelvin is positive and finite.
std::optional<Rgb> blackbody_rgb(float kelvin, SpectrumUse use = SpectrumUse::Illuminant);
// XYZ of a blackbody, normalised to Y = 1 (for tests of the chromaticity).
Vec3f blackbody_xyz(float kelvin);

// pbrt-v4's named spectra; empty for names it does not ship.
std::optional<PiecewiseSpectrum> named_spectrum(std::string_view name);
std::optional<Rgb> named_spectrum_rgb(std::string_view name, SpectrumUse use);
// The known names closest to `name` (edit distance, ties in pbrt's order), for messages.
std::vector<std::string> nearest_named_spectra(std::string_view name, size_t count = 3);

// A conductor's spectral eta and k reduced together (the fit above).
RgbComplexIor conductor_rgb_ior(const PiecewiseSpectrum& eta, const PiecewiseSpectrum& k);
// The fit for pbrt's "metal-NAME-eta" / "metal-NAME-k" pair, e.g. metal = "Cu"; empty for other names.
std::optional<RgbComplexIor> named_conductor_ior(std::string_view metal);

}  // namespace kiln
