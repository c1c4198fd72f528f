// Small value types for 2-D and 3-D vectors (points, directions and normals share Vec3f).
#pragma once
#include "core/math.h"

namespace kiln {

struct Vec2f {
  float x = 0, y = 0;
  constexpr Vec2f() = default;
  constexpr Vec2f(float x_, float y_) : x(x_), y(y_) {}
  constexpr float operator[](int i) const { return i == 0 ? x : y; }
  constexpr Vec2f operator+(Vec2f b) const { return {x + b.x, y + b.y}; }
  constexpr Vec2f operator-(Vec2f b) const { return {x - b.x, y - b.y}; }
  constexpr Vec2f operator*(float s) const { return {x * s, y * s}; }
};

struct Vec3f {
  float x = 0, y = 0, z = 0;
  constexpr Vec3f() = default;
  constexpr Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3f(float s) : x(s), y(s), z(s) {}
  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3f operator-() const { return {-x, -y, -z}; }
  constexpr Vec3f operator+(Vec3f b) const { return {x + b.x, y + b.y, z + b.z}; }
  constexpr Vec3f operator-(Vec3f b) const { return {x - b.x, y - b.y, z - b.z}; }
  constexpr Vec3f operator*(Vec3f b) const { return {x * b.x, y * b.y, z * b.z}; }
  constexpr Vec3f operator/(Vec3f b) const { return {x / b.x, y / b.y, z / b.z}; }
  constexpr Vec3f operator*(float s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3f operator/(float s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3f& operator+=(Vec3f b) { x += b.x; y += b.y; z += b.z; return *this; }
  constexpr Vec3f& operator-=(Vec3f b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
  constexpr Vec3f& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
  constexpr bool operator==(const Vec3f&) const = default;
};

constexpr Vec3f operator*(float s, Vec3f v) { return v * s; }
constexpr float dot(Vec3f a, Vec3f b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float absdot(Vec3f a, Vec3f b) { return std::abs(dot(a, b)); }
constexpr Vec3f cross(Vec3f a, Vec3f b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length_squared(Vec3f v) { return dot(v, v); }
inline float length(Vec3f v) { return std::sqrt(dot(v, v)); }
inline Vec3f normalize(Vec3f v) { return v / length(v); }
inline Vec3f abs(Vec3f v) { return {std::abs(v.x), std::abs(v.y), std::abs(v.z)}; }
inline Vec3f min(Vec3f a, Vec3f b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3f max(Vec3f a, Vec3f b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
inline float max_component(Vec3f v) { return std::max(v.x, std::max(v.y, v.z)); }
inline float min_component(Vec3f v) { return std::min(v.x, std::min(v.y, v.z)); }
inline int max_dimension(Vec3f v) { return (v.x > v.y) ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2); }
inline bool is_finite(Vec3f v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
// Mirror v about n (both pointing away from the surface).
inline Vec3f reflect(Vec3f v, Vec3f n) { return 2.0f * dot(v, n) * n - v; }
inline Vec3f face_forward(Vec3f n, Vec3f v) { return dot(n, v) < 0.0f ? -n : n; }

}  // namespace kiln
