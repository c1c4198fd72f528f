// pbrt-v4's quadric surfaces in their own object space: the geometry both the accelerators (intersection,
// renderer/accel/quadric_intersect.h) and the lights (area sampling, lights/quadric_light.h) work from.
//   Disk      z = height, inner_radius <= sqrt(x^2 + y^2) <= radius, 0 <= phi <= phi_max
//   Cylinder  x^2 + y^2 = radius^2, z_min <= z <= z_max, 0 <= phi <= phi_max
//   Sphere    |p| = radius, z_min <= z <= z_max, 0 <= phi <= phi_max (a partial sphere; whole spheres are
//             SphereShape, with their own cone sampling)
// phi = atan2(y, x) in [0, 2 pi). Surface parameters (u, v) are pbrt-v4's: u = phi / phi_max; v = (radius - r) /
// (radius - inner_radius) on the disk, (z - z_min) / (z_max - z_min) on the cylinder, (theta - theta(z_min)) /
// (theta(z_max) - theta(z_min)) on the sphere (theta = acos(z / radius)). The natural normal, along
// dp/du x dp/dv, is +z on the disk and outward on the cylinder and the sphere.
// Parameters must be valid (make_quadric checks them): radius > 0, 0 <= inner_radius < radius, z_min < z_max
// (within [-radius, radius] for the sphere), phi_max in (0, 2 pi].
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "core/bounds.h"
#include "core/math.h"
#include "core/vec.h"

namespace kiln {

enum class QuadricType : uint8_t { Disk, Cylinder, Sphere };

struct Quadric {
  QuadricType type = QuadricType::Disk;
  float radius = 1.0f;
  float inner_radius = 0.0f;          // disk
  float height = 0.0f;                // disk
  float z_min = -1.0f, z_max = 1.0f;  // cylinder, sphere
  float phi_max = 2.0f * kPi;         // radians

  bool full_turn() const { return phi_max >= 2.0f * kPi; }
  float area() const {
    switch (type) {
      case QuadricType::Disk: return 0.5f * phi_max * (radius * radius - inner_radius * inner_radius);
      case QuadricType::Cylinder:
      case QuadricType::Sphere: return phi_max * radius * (z_max - z_min);  // Archimedes for the sphere's zone
    }
    return 0.0f;
  }
  Bounds3f bounds() const {
    if (type == QuadricType::Disk) return {{-radius, -radius, height}, {radius, radius, height}};
    return {{-radius, -radius, z_min}, {radius, radius, z_max}};
  }
  // The unit natural normal at a point of the surface.
  Vec3f normal(Vec3f p) const {
    switch (type) {
      case QuadricType::Disk: return {0.0f, 0.0f, 1.0f};
      case QuadricType::Cylinder: return Vec3f(p.x, p.y, 0.0f) / radius;
      case QuadricType::Sphere: return p / radius;
    }
    return {0.0f, 0.0f, 1.0f};
  }
  // The point of the surface nearest to p along the shape's own radial direction (a hit point computed as o + t d,
  // put back onto the surface).
  Vec3f project(Vec3f p) const {
    switch (type) {
      case QuadricType::Disk: return {p.x, p.y, height};
      case QuadricType::Cylinder: {
        const float r = std::sqrt(p.x * p.x + p.y * p.y);
        return r > 0.0f ? Vec3f(p.x * (radius / r), p.y * (radius / r), p.z) : p;
      }
      case QuadricType::Sphere: {
        const float r = length(p);
        return r > 0.0f ? p * (radius / r) : p;
      }
    }
    return p;
  }
  static float phi_of(Vec3f p) {
    const float phi = std::atan2(p.y, p.x);
    return phi < 0.0f ? phi + 2.0f * kPi : phi;
  }
  // Whether a point of the (unbounded) surface lies within the shape's phi and z (or radius) limits.
  bool contains(Vec3f p) const {
    if (type == QuadricType::Disk) {
      const float r2 = p.x * p.x + p.y * p.y;
      if (r2 > radius * radius || r2 < inner_radius * inner_radius) return false;
    } else if (p.z < z_min || p.z > z_max) {
      return false;
    }
    return full_turn() || phi_of(p) <= phi_max;
  }
  Vec2f uv(Vec3f p) const {
    const float u = phi_of(p) / phi_max;
    switch (type) {
      case QuadricType::Disk: return {u, (radius - std::sqrt(p.x * p.x + p.y * p.y)) / (radius - inner_radius)};
      case QuadricType::Cylinder: return {u, (p.z - z_min) / (z_max - z_min)};
      case QuadricType::Sphere: {
        const float theta = safe_acos(p.z / radius), theta_min = safe_acos(z_min / radius);
        return {u, (theta - theta_min) / (safe_acos(z_max / radius) - theta_min)};
      }
    }
    return {u, 0.0f};
  }
  // dp/du and dp/dv at a surface point (pbrt-v4's parametrisation above).
  void derivatives(Vec3f p, Vec3f& dpdu, Vec3f& dpdv) const {
    dpdu = Vec3f(-p.y, p.x, 0.0f) * phi_max;
    switch (type) {
      case QuadricType::Disk: {
        const float r = std::sqrt(p.x * p.x + p.y * p.y);
        dpdv = r > 0.0f ? Vec3f(p.x, p.y, 0.0f) * ((inner_radius - radius) / r) : Vec3f(inner_radius - radius, 0, 0);
        break;
      }
      case QuadricType::Cylinder: dpdv = {0.0f, 0.0f, z_max - z_min}; break;
      case QuadricType::Sphere: {
        const float theta_min = safe_acos(z_min / radius), theta_max = safe_acos(z_max / radius);
        const float ring = std::sqrt(p.x * p.x + p.y * p.y);
        const float cos_phi = ring > 0.0f ? p.x / ring : 1.0f, sin_phi = ring > 0.0f ? p.y / ring : 0.0f;
        const float sin_theta = safe_sqrt(1.0f - sqr(p.z / radius));
        dpdv = Vec3f(p.z * cos_phi, p.z * sin_phi, -radius * sin_theta) * (theta_max - theta_min);
        break;
      }
    }
  }
  // A point distributed uniformly over the surface's area, from u in [0, 1)^2.
  Vec3f sample_area(Vec2f u) const {
    const float phi = u.y * phi_max;
    const float c = std::cos(phi), s = std::sin(phi);
    switch (type) {
      case QuadricType::Disk: {
        const float r = std::sqrt(lerp(u.x, inner_radius * inner_radius, radius * radius));
        return {r * c, r * s, height};
      }
      case QuadricType::Cylinder: return {radius * c, radius * s, lerp(u.x, z_min, z_max)};
      case QuadricType::Sphere: {  // uniform in z (Archimedes), uniform in phi
        const float z = lerp(u.x, z_min, z_max);
        const float ring = safe_sqrt(radius * radius - z * z);
        return {ring * c, ring * s, z};
      }
    }
    return {};
  }
};

// A quadric from pbrt's parameters (phi_max in degrees, clamped to [0, 360] as pbrt does; the sphere's z range
// clamped to [-radius, radius] and both z ranges put in order). Returns a message instead when the shape is
// degenerate or invalid: a radius that is not positive, an inner radius outside [0, radius), an empty z range or
// phi_max of 0.
struct QuadricOrError {
  std::optional<Quadric> quadric;
  std::string error;
};
inline QuadricOrError make_quadric(QuadricType type, float radius, float inner_radius, float height, float z_min,
                                   float z_max, float phi_max_deg) {
  if (!(radius > 0.0f) || !std::isfinite(radius)) return {std::nullopt, "\"radius\" must be positive"};
  Quadric q;
  q.type = type;
  q.radius = radius;
  q.phi_max = radians(std::clamp(phi_max_deg, 0.0f, 360.0f));
  if (!(q.phi_max > 0.0f)) return {std::nullopt, "\"phimax\" must be positive"};
  if (type == QuadricType::Disk) {
    if (!(inner_radius >= 0.0f) || !(inner_radius < radius))
      return {std::nullopt, "\"innerradius\" must lie in [0, radius)"};
    if (!std::isfinite(height)) return {std::nullopt, "\"height\" must be finite"};
    q.inner_radius = inner_radius;
    q.height = height;
    return {q, ""};
  }
  if (!std::isfinite(z_min) || !std::isfinite(z_max)) return {std::nullopt, "\"zmin\" and \"zmax\" must be finite"};
  q.z_min = std::min(z_min, z_max);
  q.z_max = std::max(z_min, z_max);
  if (type == QuadricType::Sphere) {
    q.z_min = std::clamp(q.z_min, -radius, radius);
    q.z_max = std::clamp(q.z_max, -radius, radius);
  }
  if (!(q.z_max > q.z_min)) return {std::nullopt, "\"zmin\" and \"zmax\" leave no surface"};
  return {q, ""};
}

}  // namespace kiln
