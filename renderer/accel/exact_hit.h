// Double-precision referee for check-bvh: where Embree and the BVH disagree, re-intersects the primitives they
// reported in double precision (world-space vertices and ray, no shear, no float rounding of t) to tell which
// accelerator was wrong: a spurious hit (the primitive is actually behind the origin or beside the ray), a missed
// genuine hit, or a farther primitive reported as the closest. Quadrics are re-intersected in their object space
// (through the inverse transform in double) with their limits in z, radius and phi as further edges.
#pragma once
#include "renderer/accel/accelerator.h"

namespace kiln {

// How close to an edge or silhouette float tests may legitimately decide either way: float computations relative
// to the ray origin are off by a few ulps of the distance between origin and vertices (or sphere centre), so the
// band is kEdgeNoiseUlps float epsilons of that distance, measured in world units from the edge.
inline constexpr double kEdgeNoiseUlps = 64.0;

struct ExactHit {
  bool hit = false;        // the ray meets the primitive with t in [ray.tmin, ray.tmax]
  bool in_range = false;   // the line (inside or just beside the primitive) crosses it with t in [tmin, tmax]
  double t = 0;            // that crossing's t (nearest in range for spheres)
  bool near_edge = false;  // the crossing is within float noise of the primitive's edge or silhouette
  Vec2f where;             // the crossing's hit coordinates (a triangle's b1, b2; a quadric's (u, v)): for alpha
  uint32_t root = 0;       // a quadric's: which crossing of its line (quadric_intersect.h)
};

ExactHit exact_hit(const WorldGeometry& g, const Ray& ray, uint32_t shape, uint32_t prim);

}  // namespace kiln
