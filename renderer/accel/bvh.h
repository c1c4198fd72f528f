// Kiln's own accelerator: a two-level BVH built with the binned SAH builder of bvh_build.h.
//
// Layout. The world tree flattens every world-space mesh triangle and every sphere/ellipsoid into one BVH, and
// adds one primitive per instance; an instance leaf primitive transforms the ray into object space (in double,
// object_ray.h) and continues in its prototype's own BVH (built once per prototype, shared by all its
// instances). So the common case, meshes placed in world space, is a single tree with no per-mesh boxes
// overlapping one another.
//
// Traversal. The binary SAH tree (32-byte nodes, built with leaf cost counted in 4-triangle blocks) is collapsed
// into a 4-wide tree: 128-byte nodes holding their four child boxes as SoA rows, tested against one ray with SSE
// (x86-64 baseline, no -march needed). Triangle leaves are stored as packets of four triangles in SoA form, in
// leaf order, and tested with an SSE version of the watertight test that is bit-identical lane by lane to the
// scalar one. Traversal is stack-based and ordered (nearest child first, farther ones pushed with their entry
// distance and skipped once a closer hit is known), with a precomputed inverse direction and Ize's conservative
// slab test. Leaves hold one kind of primitive only (triangles, or spheres/instances).
//
// Ray conventions are Embree's: hits with t in [ray.tmin, ray.tmax] (no epsilon), triangles tested with the
// watertight test of triangle_intersect.h, spheres with sphere_intersect.h, quadrics with quadric_intersect.h,
// Hit::ng from surface_point.h; rays that Embree would reject (traceable_ray.h) miss. Alpha cut-outs: a triangle
// packet's lanes on shapes with alpha are filtered through renderer/accel/alpha.h in a traversal instantiated for
// scenes with alpha only (scenes without take the other instantiation, one branch per query); quadrics test it on
// each root.
#pragma once
#include <memory>
#include <optional>

#include "renderer/accel/accelerator.h"
#include "renderer/accel/bvh_build.h"

namespace kiln {

struct BvhOptions {
  BvhBuildOptions build{.max_leaf_size = 8, .leaf_block = 4};  // leaves are tested as 4-wide packets
  // Test hook: leave world primitive k out of the BVH (primitives are numbered world-mesh triangles first, in
  // shape order, then spheres, instances, moving meshes and quadrics) so tests can show that check_bvh detects a
  // broken accelerator.
  std::optional<size_t> debug_drop_primitive;
};

struct BvhStats {
  BvhTreeStats world;     // the world (top-level) tree as built (binary)
  size_t wide_nodes = 0;  // 4-wide nodes of the world tree after collapsing
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
