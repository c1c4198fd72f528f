// Kiln's own accelerator: a two-level BVH built with the binned SAH builder of bvh_build.h.
//
// Layout. The world tree flattens every world-space mesh triangle and every sphere/ellipsoid into one BVH, and
// adds one primitive per instance; an instance leaf primitive transforms the ray into object space and
// continues in its prototype's own BVH (built once per prototype, shared by all its instances). So the common
// case, meshes placed in world space, is a single tree with no per-mesh boxes overlapping one another.
// Primitive data is stored in leaf order (triangle vertices copied next to each other) for locality.
//
// Ray conventions are Embree's: hits with t in [ray.tmin, ray.tmax] (no epsilon), triangles tested with the
// watertight test of triangle_intersect.h, spheres with sphere_intersect.h, Hit::ng from hit_point.h.
#pragma once
#include <memory>
#include <optional>

#include "renderer/accel/accelerator.h"
#include "renderer/accel/bvh_build.h"

namespace kiln {

struct BvhOptions {
  BvhBuildOptions build;
  // Test hook: leave world primitive k out of the BVH (primitives are numbered world-mesh triangles first, in
  // shape order, then spheres, then instances) so tests can show that check_bvh detects a broken accelerator.
  std::optional<size_t> debug_drop_primitive;
};

struct BvhStats {
  BvhTreeStats world;  // the world (top-level) tree
  size_t prototype_trees = 0;
  size_t prototype_nodes = 0;
  double build_seconds = 0;
  size_t bytes = 0;
};

class Bvh final : public Accelerator {
 public:
  explicit Bvh(const WorldGeometry& geometry, const BvhOptions& options = {});
  ~Bvh() override;
  Bvh(const Bvh&) = delete;
  Bvh& operator=(const Bvh&) = delete;

  bool intersect(const Ray& ray, Hit& hit) const override;
  bool occluded(const Ray& ray) const override;
  AccelStats stats() const override;
  const BvhStats& bvh_stats() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace kiln
