#include "renderer/accel/bvh_build.h"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "core/rng.h"

namespace kiln {
namespace {

bool contains(const Bounds3f& outer, const Bounds3f& inner) {
  return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z && outer.hi.x >= inner.hi.x &&
         outer.hi.y >= inner.hi.y && outer.hi.z >= inner.hi.z;
}

std::vector<Bounds3f> random_boxes(size_t n, uint64_t seed, float size) {
  Rng rng(seed, 0);
  std::vector<Bounds3f> b(n);
  for (auto& x : b) {
    const Vec3f p(rng.next_float() * 100, rng.next_float() * 100, rng.next_float() * 10);
    x = Bounds3f(p, p + Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) * size);
  }
  return b;
}

// Checks every structural invariant and returns the number of leaves.
size_t check_tree(const BvhBuildResult& r, const std::vector<Bounds3f>& prims, uint32_t max_leaf) {
  std::vector<int> seen(prims.size(), 0);
  std::vector<uint32_t> stack{kBvhRoot};
  size_t leaves = 0;
  while (!stack.empty()) {
    const uint32_t i = stack.back();
    stack.pop_back();
    const BvhNode& n = r.nodes[i];
    if (n.is_leaf()) {
      ++leaves;
      EXPECT_LE(n.count, max_leaf);
      for (uint32_t k = n.offset; k < n.offset + n.count; ++k) {
        ++seen[r.order[k]];
        EXPECT_TRUE(contains(n.bounds(), prims[r.order[k]])) << "leaf box must hold its primitives";
      }
      continue;
    }
    EXPECT_EQ(n.offset % 2, 0u) << "siblings share a cache line";
    for (uint32_t c : {n.offset, n.offset + 1}) {
      EXPECT_LT(c, r.nodes.size());
      EXPECT_TRUE(contains(n.bounds(), r.nodes[c].bounds())) << "child box inside its parent";
      stack.push_back(c);
    }
  }
  for (size_t p = 0; p < prims.size(); ++p) EXPECT_EQ(seen[p], 1) << "primitive " << p;
  return leaves;
}

TEST(BvhBuild, InvariantsAndStats) {
  const auto prims = random_boxes(5000, 1, 2.0f);
  BvhBuildOptions opt;
  const BvhBuildResult r = build_bvh(prims, opt);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(r.nodes.data()) % 64, 0u) << "nodes are cache-line aligned";
  const size_t leaves = check_tree(r, prims, opt.max_leaf_size);
  const BvhTreeStats s = bvh_tree_stats(r.nodes, opt);
  EXPECT_EQ(s.leaves, leaves);
  EXPECT_EQ(s.primitives, prims.size());
  EXPECT_EQ(s.nodes, 2 * leaves - 1);
  EXPECT_EQ(r.nodes.size(), s.nodes + 1) << "depth-first layout leaves no holes but the padding node";
  EXPECT_EQ(std::accumulate(s.leaf_size_histogram.begin(), s.leaf_size_histogram.end(), size_t(0)), leaves);
  EXPECT_GT(s.sah_cost, 1.0);
  EXPECT_LT(s.max_depth, 60u);
  // A real SAH tree over 5000 boxes costs far less than testing them all.
  EXPECT_LT(s.sah_cost, 0.02 * double(prims.size()));
}

TEST(BvhBuild, SahBeatsLeafOnlyWhenWorthIt) {
  // Two far-apart clusters: the SAH must separate them at the root.
  std::vector<Bounds3f> prims;
  for (int i = 0; i < 4; ++i) prims.push_back(Bounds3f(Vec3f(float(i) * 0.01f), Vec3f(float(i) * 0.01f + 0.01f)));
  for (int i = 0; i < 4; ++i)
    prims.push_back(Bounds3f(Vec3f(100.0f + float(i) * 0.01f), Vec3f(100.02f + float(i) * 0.01f)));
  const BvhBuildResult r = build_bvh(prims);
  ASSERT_FALSE(r.nodes[kBvhRoot].is_leaf());
  const BvhNode& a = r.nodes[r.nodes[kBvhRoot].offset];
  const BvhNode& b = r.nodes[r.nodes[kBvhRoot].offset + 1];
  EXPECT_LT(std::min(a.hi.x, b.hi.x), 1.0f);
  EXPECT_GT(std::max(a.lo.x, b.lo.x), 99.0f);
  // Eight overlapping identical-size boxes in one spot are cheapest as a single leaf.
  std::vector<Bounds3f> blob(8, Bounds3f(Vec3f(0.0f), Vec3f(1.0f)));
  for (int i = 0; i < 8; ++i) blob[size_t(i)] = Bounds3f(Vec3f(float(i) * 1e-3f), Vec3f(1.0f + float(i) * 1e-3f));
  EXPECT_TRUE(build_bvh(blob).nodes[kBvhRoot].is_leaf());
}

TEST(BvhBuild, CoincidentCentroidsStillRespectLeafSize) {
  // Nested boxes around one centre: no SAH split can separate them, so the builder falls back to halving the
  // range; their different sizes make every child box check meaningful.
  std::vector<Bounds3f> prims;
  for (int i = 0; i < 1000; ++i) prims.push_back(Bounds3f(Vec3f(2.0f - float(i)), Vec3f(2.0f + float(i))));
  const BvhBuildResult r = build_bvh(prims);
  check_tree(r, prims, 8);
}

TEST(BvhBuild, EmptyAndSingle) {
  const BvhBuildResult e = build_bvh({});
  ASSERT_GE(e.nodes.size(), 1u);
  EXPECT_TRUE(e.nodes[kBvhRoot].bounds().empty());
  EXPECT_TRUE(e.order.empty());
  const std::vector<Bounds3f> one{Bounds3f(Vec3f(0.0f), Vec3f(1.0f))};
  const BvhBuildResult r = build_bvh(one);
  EXPECT_TRUE(r.nodes[kBvhRoot].is_leaf());
  EXPECT_EQ(r.nodes[kBvhRoot].count, 1u);
}

TEST(BvhBuild, LargeParallelBuildIsDeterministic) {
  // Large enough for parallel binning and parallel subtrees.
  const auto prims = random_boxes(200000, 9, 0.5f);
  const BvhBuildResult a = build_bvh(prims), b = build_bvh(prims);
  check_tree(a, prims, 8);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(a.order, b.order);
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    ASSERT_EQ(a.nodes[i].offset, b.nodes[i].offset) << i;
    ASSERT_EQ(a.nodes[i].count, b.nodes[i].count) << i;
    ASSERT_EQ(a.nodes[i].lo, b.nodes[i].lo) << i;
  }
}

}  // namespace
}  // namespace kiln
