// Linear RGB radiance / reflectance triple.
#pragma once
#include "core/math.h"

namespace kiln {

struct Rgb {
  float r = 0, g = 0, b = 0;
  constexpr Rgb() = default;
  constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
  constexpr explicit Rgb(float s) : r(s), g(s), b(s) {}
  constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr Rgb operator+(Rgb o) const { return {r + o.r, g + o.g, b + o.b}; }
  constexpr Rgb operator-(Rgb o) const { return {r - o.r, g - o.g, b - o.b}; }
  constexpr Rgb operator*(Rgb o) const { return {r * o.r, g * o.g, b * o.b}; }
  constexpr Rgb operator/(Rgb o) const { return {r / o.r, g / o.g, b / o.b}; }
  constexpr Rgb operator*(float s) const { return {r * s, g * s, b * s}; }
  constexpr Rgb operator/(float s) const { return {r / s, g / s, b / s}; }
  constexpr Rgb& operator+=(Rgb o) { r += o.r; g += o.g; b += o.b; return *this; }
  constexpr Rgb& operator*=(Rgb o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
  constexpr Rgb& operator*=(float s) { r *= s; g *= s; b *= s; return *this; }
  constexpr bool operator==(const Rgb&) const = default;
  constexpr bool is_black() const { return r == 0.0f && g == 0.0f && b == 0.0f; }
  float max_component() const { return std::max(r, std::max(g, b)); }
  float average() const { return (r + g + b) * (1.0f / 3.0f); }
  // Rec. 709 / sRGB luminance.
  constexpr float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
  bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
  bool has_negative() const { return r < 0.0f || g < 0.0f || b < 0.0f; }
};

constexpr Rgb operator*(float s, Rgb c) { return c * s; }
inline Rgb exp(Rgb c) { return {std::exp(c.r), std::exp(c.g), std::exp(c.b)}; }
inline Rgb pow(Rgb c, float e) { return {std::pow(c.r, e), std::pow(c.g, e), std::pow(c.b, e)}; }

// The sRGB transfer curve (IEC 61966-2-1) undone: an encoded value in [0, 1] to linear.
inline float srgb_to_linear(float v) {
  return v <= 0.04045f ? v * (1.0f / 12.92f) : std::pow((v + 0.055f) * (1.0f / 1.055f), 2.4f);
}

}  // namespace kiln
