// Binned SAH builder for a binary BVH over abstract primitives given by their bounds (Wald 2007, "On fast
// Construction of SAH-based Bounding Volume Hierarchies"). Splits are chosen among bins_per_axis candidate
// planes on each of the three axes; a node becomes a leaf when that is cheaper under the SAH than its best
// split (or it is small enough and cannot be split), up to max_leaf_size primitives. Large subtrees are built in
// parallel with TBB and the top levels bin in parallel. The result is deterministic (independent of thread
// timing): the tree is relaid out depth-first after the parallel build.
#pragma once
#include <tbb/cache_aligned_allocator.h>

#include <cstdint>
#include <span>
#include <vector>

#include "core/bounds.h"

namespace kiln {

// 32 bytes. Siblings are stored as a pair (2k, 2k+1) so one 64-byte cache line holds both child boxes; the root
// is node 0 and node 1 is unused padding.
struct BvhNode {
  Vec3f lo;
  uint32_t offset = 0;  // interior: index of the first child (the second is offset + 1); leaf: first primitive
  Vec3f hi;
  uint32_t count = 0;  // number of primitives of a leaf; 0 for interior nodes
  bool is_leaf() const { return count != 0; }
  Bounds3f bounds() const {
    Bounds3f b;  // not Bounds3f(lo, hi), which would turn an empty box inside out
    b.lo = lo;
    b.hi = hi;
    return b;
  }
};
static_assert(sizeof(BvhNode) == 32);

inline constexpr uint32_t kBvhRoot = 0;

struct BvhBuildOptions {
  int bins_per_axis = 16;          // clamped to [2, 32]
  uint32_t max_leaf_size = 8;      // a leaf never holds more unless its primitives cannot be separated
  uint32_t leaf_block = 1;         // primitives tested together (SIMD width): a leaf costs ceil(n / leaf_block)
  float traversal_cost = 1.0f;     // SAH cost of visiting an interior node ...
  float intersection_cost = 1.0f;  // ... relative to intersecting one block of primitives
};

struct BvhBuildResult {
  std::vector<BvhNode, tbb::cache_aligned_allocator<BvhNode>> nodes;  // cache-line aligned
  std::vector<uint32_t> order;  // leaf primitive slot i holds input primitive order[i]
};

// Empty prim_bounds gives a single empty leaf. When prim_class is given (one entry per primitive), every leaf
// holds primitives of one class only (e.g. triangles apart from spheres, so leaves can be stored as SIMD packets).
BvhBuildResult build_bvh(std::span<const Bounds3f> prim_bounds, const BvhBuildOptions& options = {},
                         std::span<const uint8_t> prim_class = {});

struct BvhTreeStats {
  double sah_cost = 0;  // expected cost of a random ray hitting the root box, in BvhBuildOptions units
  size_t nodes = 0, leaves = 0, max_depth = 0, primitives = 0;
  std::vector<size_t> leaf_size_histogram;  // [k] = number of leaves with k primitives
};

BvhTreeStats bvh_tree_stats(std::span<const BvhNode> nodes, const BvhBuildOptions& options = {});

}  // namespace kiln
