// pbrt-v4 spectra reduced to Kiln's linear RGB (Rec. 709 primaries, D65 white, like pbrt's default "srgb" colour
// space). pbrt renders spectrally; Kiln renders RGB, so every spectral parameter becomes one RGB triple here:
//   * illuminants (light "L" / "I"): pbrt divides an emission spectrum by its luminance ("scale so that radiance
//     is equivalent to 1 nit"), so only its chromaticity survives: the RGB of the spectrum's XYZ with Y = 1. An RGB
//     illuminant is taken as written (pbrt multiplies it by the colour space's D65 illuminant and divides by that
//     illuminant's luminance, so "rgb L [1 1 1]" is RGB 1);
//   * reflectances (albedos): the RGB of the spectrum's XYZ under an equal-energy white, divided per channel by the
//     RGB of a constant 1, so a flat spectrum c gives (c, c, c);
//   * unbounded quantities (conductor eta and k, dielectric eta): the value at 630, 532 and 465 nm.
// XYZ uses the CIE 1931 2-degree observer through the analytic multi-lobe fit of Wyman, Sloan and Shirley
// ("Simple Analytic Approximations to the CIE XYZ Color Matching Functions", JCGT 2(2), 2013), integrated over
// 360-830 nm in 1 nm steps.
#pragma once
#include <optional>
#include <span>
#include <string_view>

#include "core/color.h"
#include "core/vec.h"

namespace kiln {

enum class SpectrumUse { Illuminant, Albedo, Unbounded };

// CIE 1931 colour-matching functions (x-bar, y-bar, z-bar) at a wavelength in nanometres (analytic fit).
Vec3f cie_xyz_matching(float lambda_nm);
Rgb xyz_to_linear_srgb(Vec3f xyz);
// Chromaticity (x, y) at luminance 1 as linear sRGB.
Rgb chromaticity_to_linear_srgb(float x, float y);

// Planck's law at `kelvin`, as an illuminant (luminance 1); empty unless kelvin is positive and finite.
std::optional<Rgb> blackbody_rgb(float kelvin);
// XYZ of a blackbody, normalised to Y = 1 (for tests of the chromaticity).
Vec3f blackbody_xyz(float kelvin);

// A piecewise-linear spectrum given as (wavelength nm, value) pairs with increasing wavelengths; zero outside
// its range. The caller checks the pairs (at least one, increasing).
Rgb sampled_spectrum_rgb(std::span<const float> lambda_nm, std::span<const float> values, SpectrumUse use);

// pbrt's named spectra that Kiln knows, reduced for `use`: the standard illuminants D65 (RGB 1), D50, A, ACES D60;
// the metals' "metal-{Ag,Al,Au,Cu,CuZn}-{eta,k}" as the commonly used RGB reductions of their measured optical
// constants; the glasses "glass-{BK7,BAF10,FK51A,LASF9,F5}" as their catalogue index n_d (587.6 nm) in all
// three channels. Empty for names it does not know.
std::optional<Rgb> named_spectrum_rgb(std::string_view name, SpectrumUse use);

}  // namespace kiln
