// The interface every ray-query backend implements (Embree, the in-house BVH).
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "core/ray.h"
#include "renderer/accel/geometry.h"

namespace kiln {

inline constexpr uint32_t kInvalidId = 0xffffffffu;

struct Hit {
  float t = kInfinity;
  uint32_t shape = kInvalidId;  // index into WorldGeometry::shapes
  uint32_t prim = kInvalidId;   // triangle index within the (prototype) mesh; 0 for spheres
  float u = 0, v = 0;           // triangle barycentrics of vertices 1 and 2 (b0 = 1 - u - v)
  Vec3f ng;                     // world-space geometric normal, not normalised; for triangles (v1-v0)x(v2-v0)
  bool valid() const { return shape != kInvalidId; }
};

struct AccelStats {
  std::string name;
  double build_seconds = 0;
  size_t bytes = 0;
};

class Accelerator {
 public:
  virtual ~Accelerator() = default;
  // Closest hit with t in [ray.tmin, ray.tmax]; on success fills hit and returns true.
  virtual bool intersect(const Ray& ray, Hit& hit) const = 0;
  // Any hit with t in [ray.tmin, ray.tmax].
  virtual bool occluded(const Ray& ray) const = 0;
  virtual AccelStats stats() const = 0;
};

enum class AccelKind { Embree, Bvh };

// Builds the chosen accelerator over geometry (which must outlive it). threads: 0 = all.
std::unique_ptr<Accelerator> make_accelerator(AccelKind kind, const WorldGeometry& geometry);

}  // namespace kiln
