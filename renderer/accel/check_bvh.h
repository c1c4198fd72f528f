// check-bvh: cross-checks the in-house BVH against Embree ray by ray. Camera rays come from the caller; from each
// camera ray's Embree hit a cosine-distributed bounce ray (about the geometric normal, on the side the camera ray
// came from) and a shadow ray towards a uniformly random point of the scene bounds are spawned with
// offset_ray_origin, and every ray goes through both accelerators. Compared: hit versus miss, distance and
// primitive; a different primitive at an agreeing distance is an edge tie (a ray through a shared edge or vertex
// may legitimately report either triangle) and is counted apart from disagreements.
//
// Every disagreement is refereed in double precision (exact_hit.h) and blamed on Embree, on the BVH, or left
// unresolved (within float noise of an edge or silhouette, or both wrong). Embree is not infallible: its t is
// computed in float from vertices relative to the origin, so next to large triangles (the ground planes of
// course scenes) it finds the surface a bounce ray has just left again at t ~ 1e-6. The check passes when the
// disagreements not blamed on Embree are <= kCheckBvhMaxDisagreementRate of all rays.
//
// Distances agree when they are within kCheckBvhDistanceTolerance of each other relative to the distance, or
// when the two hit points are within kCheckBvhHitPointUlps ulps of the hit point's largest coordinate. The second
// clause matters for short rays (bounces into concave regions): Embree's own t there is off by up to 2e-5
// relative (measured against a double-precision reference on the killeroo; the BVH's by 2e-6), a difference
// below one ulp of the hit position, which no renderer can see.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "core/rng.h"
#include "renderer/accel/accelerator.h"
#include "renderer/accel/bvh_build.h"

namespace kiln {

inline constexpr float kCheckBvhDistanceTolerance = 1e-5f;
inline constexpr float kCheckBvhHitPointUlps = 16.0f;
inline constexpr double kCheckBvhMaxDisagreementRate = 1e-5;

struct CheckBvhOptions {
  size_t rays = 100000;  // camera rays; each may add one bounce and one shadow ray
  uint64_t seed = 1;
};

struct CheckBvhKind {
  size_t rays = 0, disagreements = 0, edge_ties = 0;
  size_t embree_faults = 0, bvh_faults = 0, unresolved = 0;  // disagreements by the referee's verdict
};

struct CheckBvhReport {
  CheckBvhKind camera, bounce, shadow;
  size_t total_rays() const { return camera.rays + bounce.rays + shadow.rays; }
  size_t total_disagreements() const { return camera.disagreements + bounce.disagreements + shadow.disagreements; }
  // Disagreements the BVH may be to blame for (all but those the referee pinned on Embree).
  size_t total_bvh_suspect() const {
    return camera.bvh_faults + camera.unresolved + bounce.bvh_faults + bounce.unresolved + shadow.bvh_faults +
           shadow.unresolved;
  }
  BvhTreeStats bvh;  // the world tree: SAH cost, nodes, depth, leaf-size histogram
  AccelStats embree_stats, bvh_stats;
  std::string first_disagreement;  // a description of the first one found, empty when none
  bool passed = false;
  std::string to_json() const;
};

// Builds both accelerators over geometry and compares them. camera_ray(i, rng) makes camera ray i (rng is that
// ray's own stream, seeded from options.seed and i, so the result does not depend on thread count).
CheckBvhReport check_bvh(const WorldGeometry& geometry, const std::function<Ray(size_t i, Rng&)>& camera_ray,
                         const CheckBvhOptions& options);

class Bvh;
// The same comparison for accelerators the caller built (tests use it with a deliberately corrupted Bvh).
CheckBvhReport check_bvh(const WorldGeometry& geometry, const Accelerator& embree, const Bvh& bvh,
                         const std::function<Ray(size_t i, Rng&)>& camera_ray, const CheckBvhOptions& options);

}  // namespace kiln
