// Emission of a temperature grid: the radiance of a blackbody at a temperature, tabulated on a logarithmic scale of
// temperatures by whoever knows the spectra (the pbrt loader reduces pbrt-v4's peak-normalised blackbody spectrum
// to RGB) and interpolated linearly here. The scale is fixed, so a table is just its values.
#pragma once
#include <cmath>
#include <vector>

#include "core/color.h"

namespace kiln {

// Temperatures in kelvin from kEmissionTableMinKelvin to kEmissionTableMaxKelvin, evenly spaced in log(T).
inline constexpr float kEmissionTableMinKelvin = 100.0f;
inline constexpr float kEmissionTableMaxKelvin = 100000.0f;
inline constexpr int kEmissionTableSize = 1024;

inline float emission_table_kelvin(int i) {
  const float f = float(i) / float(kEmissionTableSize - 1);
  return kEmissionTableMinKelvin * std::pow(kEmissionTableMaxKelvin / kEmissionTableMinKelvin, f);
}

// Radiance at `kelvin` from table (kEmissionTableSize values at emission_table_kelvin(i)); black at and below
// kEmissionTableMinKelvin (pbrt-v4 leaves temperatures up to 100 K dark), the last value beyond the top.
inline Rgb emission_at(const std::vector<Rgb>& table, float kelvin) {
  if (!(kelvin > kEmissionTableMinKelvin) || table.empty()) return Rgb(0.0f);
  const float x = std::log(kelvin / kEmissionTableMinKelvin) /
                  std::log(kEmissionTableMaxKelvin / kEmissionTableMinKelvin) * float(kEmissionTableSize - 1);
  if (x >= float(kEmissionTableSize - 1)) return table.back();
  const int i = int(x);
  const float f = x - float(i);
  return table[size_t(i)] * (1.0f - f) + table[size_t(i) + 1] * f;
}

}  // namespace kiln
