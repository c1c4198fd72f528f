// Scalar helpers and constants shared by every layer.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace kiln {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Largest float strictly below 1: uniform samples live in [0, kOneMinusEpsilon].
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

inline float radians(float deg) { return deg * (kPi / 180.0f); }
inline float degrees(float rad) { return rad * (180.0f / kPi); }
inline float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
inline float safe_acos(float x) { return std::acos(std::clamp(x, -1.0f, 1.0f)); }
inline float safe_asin(float x) { return std::asin(std::clamp(x, -1.0f, 1.0f)); }
inline float sqr(float x) { return x * x; }
template <typename T>
inline T lerp(float t, T a, T b) { return (1.0f - t) * a + t * b; }
inline bool is_finite(float x) { return std::isfinite(x); }

}  // namespace kiln
