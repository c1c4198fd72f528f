// The named spectra of pbrt-v4 as tabulated data (scenes/pbrt/named_spectra.cpp, generated from pbrt-v4's measured
// data by tools/pbrt_named_spectra.py): glasses ("glass-BK7", ... refractive indices), metals ("metal-Au-eta",
// "metal-Au-k", ...), standard illuminants ("stdillum-A", "stdillum-D50", "stdillum-D65", "stdillum-F1".."F12",
// "illum-acesD60"), camera sensor curves ("canon_eos_100d_r", ...), and the CIE 1931 colour-matching functions with which
// scenes/pbrt/spectrum.h reduces them to RGB.
#pragma once
#include <span>
#include <string_view>

namespace kiln {

struct NamedSpectrumData {
  std::string_view name;
  float first_nm, step_nm;           // the uniform grid of `values` when `lambda_nm` is empty
  std::span<const float> lambda_nm;  // else the wavelength of each value (increasing)
  std::span<const float> values;     // piecewise linear between the wavelengths, zero outside them
};

std::span<const NamedSpectrumData> named_spectra_data();

// The CIE 1931 2-degree standard observer: x-bar, y-bar, z-bar at first_nm, first_nm + 1, ... (1 nm steps).
struct CieObserverData {
  float first_nm;
  std::span<const float> x, y, z;
};
CieObserverData cie_1931_data();

}  // namespace kiln
