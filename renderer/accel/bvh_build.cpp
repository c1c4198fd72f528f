#include "renderer/accel/bvh_build.h"

#include <immintrin.h>  // SSE2: part of the x86-64 baseline
#include <tbb/blocked_range.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>

namespace kiln {
namespace {

constexpr int kMinBins = 2;
constexpr int kMaxBins = 32;
constexpr int kMinSmallNodeBins = 4;
constexpr uint32_t kDualBinThreshold = 256;           // smaller ranges bin into one set
constexpr uint32_t kParallelSubtreeThreshold = 4096;  // smaller subtrees are not worth a task
constexpr uint32_t kParallelBinThreshold = 32768;     // nodes this large bin their primitives in parallel
constexpr uint32_t kParallelBinGrain = 8192;
// Bounds the tree depth so fixed-size traversal stacks can never overflow (class separation may add two levels).
constexpr uint32_t kMaxDepth = 58;

// Boxes and primitives in SSE registers: the binning inner loop is a handful of vector min/max per primitive.
struct Box {
  __m128 lo = _mm_set1_ps(kInfinity), hi = _mm_set1_ps(-kInfinity);
  void extend(const Box& b) {
    lo = _mm_min_ps(lo, b.lo);
    hi = _mm_max_ps(hi, b.hi);
  }
  void extend(__m128 p) {
    lo = _mm_min_ps(lo, p);
    hi = _mm_max_ps(hi, p);
  }
  Bounds3f bounds() const {
    alignas(16) float l[4], h[4];
    _mm_store_ps(l, lo);
    _mm_store_ps(h, hi);
    Bounds3f b;
    b.lo = Vec3f(l[0], l[1], l[2]);
    b.hi = Vec3f(h[0], h[1], h[2]);
    return b;
  }
  // Half the surface area (SAH ratios only need areas up to a common factor); 0 for an empty box.
  float half_area() const {
    const __m128 d = _mm_max_ps(_mm_sub_ps(hi, lo), _mm_setzero_ps());
    const __m128 yzx = _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1));
    const __m128 p = _mm_mul_ps(d, yzx);  // dx dy, dy dz, dz dx
    const __m128 s = _mm_add_ss(_mm_add_ss(p, _mm_shuffle_ps(p, p, 1)), _mm_shuffle_ps(p, p, 2));
    return _mm_cvtss_f32(s);
  }
};

// One primitive during the build, moved (not referenced) by the partitions so every pass streams through memory.
// Its id rides in the w lane of hi (ids < 2^30 are finite floats, and w lanes are never interpreted).
struct BuildPrim {
  __m128 lo, hi;
  uint32_t id() const {
    alignas(16) uint32_t v[4];
    _mm_store_ps(reinterpret_cast<float*>(v), hi);
    return v[3];
  }
  __m128 centroid2() const { return _mm_add_ps(lo, hi); }  // twice the centroid: no multiply needed
};

// Bin boxes without default initialisers: a BinSet lives on the stack of every node and only the bins in use
// are cleared (small nodes use few).
struct BinBox {
  __m128 lo, hi;
};

struct BinSet {
  BinBox box[3][kMaxBins];
  uint32_t count[3][kMaxBins];
  BinSet() = default;
  explicit BinSet(int nb) {
    const __m128 inf = _mm_set1_ps(kInfinity), ninf = _mm_set1_ps(-kInfinity);
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < nb; ++k) {
        box[a][k] = {inf, ninf};
        count[a][k] = 0;
      }
  }
  void merge(const BinSet& o, int nb) {
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < nb; ++k) {
        box[a][k].lo = _mm_min_ps(box[a][k].lo, o.box[a][k].lo);
        box[a][k].hi = _mm_max_ps(box[a][k].hi, o.box[a][k].hi);
        count[a][k] += o.count[a][k];
      }
  }
};

// Maps (doubled) centroids of one node to bin indices on all three axes at once; the partition uses the same
// mapping as the binning so both agree exactly on which side a primitive falls.
struct BinMapping {
  __m128 lo, scale, top;
  int nb;
  BinMapping(const Box& cb, int bins) : lo(cb.lo), top(_mm_set1_ps(float(bins - 1))), nb(bins) {
    alignas(16) float ext[4], sc[4];
    _mm_store_ps(ext, _mm_sub_ps(cb.hi, cb.lo));
    for (int a = 0; a < 4; ++a) sc[a] = (a < 3 && ext[a] > 0.0f) ? float(bins) / ext[a] : 0.0f;
    scale = _mm_load_ps(sc);
  }
  bool splittable(int axis) const {
    alignas(16) float sc[4];
    _mm_store_ps(sc, scale);
    return sc[axis] > 0.0f;
  }
  __m128i operator()(__m128 c2) const {
    const __m128 f = _mm_mul_ps(_mm_sub_ps(c2, lo), scale);
    return _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), top));
  }
  int operator()(__m128 c2, int axis) const {
    alignas(16) int32_t k[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(k), (*this)(c2));
    return k[axis];
  }
};

class Builder {
 public:
  Builder(std::span<const Bounds3f> pb, std::span<const uint8_t> cls, const BvhBuildOptions& opt, BvhBuildResult& out)
      : pb_(pb), cls_(cls), opt_(opt), nb_(std::clamp(opt.bins_per_axis, kMinBins, kMaxBins)), out_(out) {}

  void run() {
    const uint32_t n = uint32_t(pb_.size());
    prims_.resize(n);
    Box b, cb;
    for (uint32_t i = 0; i < n; ++i) {
      const Bounds3f& x = pb_[i];
      prims_[i].lo = _mm_setr_ps(x.lo.x, x.lo.y, x.lo.z, 0.0f);
      prims_[i].hi = _mm_setr_ps(x.hi.x, x.hi.y, x.hi.z, std::bit_cast<float>(i));
      b.extend(Box{prims_[i].lo, prims_[i].hi});
      cb.extend(prims_[i].centroid2());
    }
    nodes_.assign(std::max<size_t>(2, 2 * size_t(n)), BvhNode{});
    build(kBvhRoot, 0, n, b, cb, 0);
    out_.order.resize(n);
    for (uint32_t i = 0; i < n; ++i) out_.order[i] = prims_[i].id();
    relayout();
  }

 private:
  std::span<const Bounds3f> pb_;
  std::span<const uint8_t> cls_;
  const BvhBuildOptions& opt_;
  int nb_;
  uint32_t blk_ = std::max<uint32_t>(1, opt_.leaf_block);
  int blk_shift_ = std::has_single_bit(blk_) ? std::countr_zero(blk_) : -1;
  BvhBuildResult& out_;
  std::vector<BuildPrim> prims_;
  std::vector<BvhNode> nodes_;  // build order; relaid out depth-first into out_.nodes
  std::atomic<uint32_t> next_{2};

  static void add_to_bins(const BuildPrim& p, const BinMapping& map, BinSet& bins) {
    alignas(16) int32_t k[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(k), map(p.centroid2()));
    for (int a = 0; a < 3; ++a) {
      BinBox& bx = bins.box[a][k[a]];
      bx.lo = _mm_min_ps(bx.lo, p.lo);
      bx.hi = _mm_max_ps(bx.hi, p.hi);
      ++bins.count[a][k[a]];
    }
  }

  // Neighbouring primitives usually fall into the same bin; alternating between two bin sets halves the chains
  // of dependent load-min-store updates on one bin.
  void bin_range(uint32_t begin, uint32_t end, const BinMapping& map, BinSet& bins) const {
    if (end - begin < kDualBinThreshold) {
      for (uint32_t i = begin; i < end; ++i) add_to_bins(prims_[i], map, bins);
      return;
    }
    BinSet other(map.nb);
    uint32_t i = begin;
    for (; i + 1 < end; i += 2) {
      add_to_bins(prims_[i], map, bins);
      add_to_bins(prims_[i + 1], map, other);
    }
    if (i < end) add_to_bins(prims_[i], map, bins);
    bins.merge(other, map.nb);
  }

  // Filled in place: a 3 KB BinSet returned by value from two return paths would be copied for every node.
  void bin(uint32_t begin, uint32_t end, const BinMapping& map, BinSet& bins) const {
    if (end - begin < kParallelBinThreshold) {
      bin_range(begin, end, map, bins);
      return;
    }
    bins = tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(begin, end, kParallelBinGrain), BinSet(map.nb),
        [&](const tbb::blocked_range<uint32_t>& r, BinSet acc) {
          bin_range(r.begin(), r.end(), map, acc);
          return acc;
        },
        [&](BinSet a, const BinSet& b) {
          a.merge(b, map.nb);
          return a;
        });
  }

  // ceil(n / block); a shift for power-of-two blocks (an integer division here would dominate the SAH sweep).
  float leaf_cost(uint32_t n) const {
    return float(blk_shift_ >= 0 ? (n + blk_ - 1) >> blk_shift_ : (n + blk_ - 1) / blk_);
  }

  static void add(const BuildPrim& p, Box& b, Box& cb) {
    b.lo = _mm_min_ps(b.lo, p.lo);
    b.hi = _mm_max_ps(b.hi, p.hi);
    cb.extend(p.centroid2());
  }

  // Hoare partition of [begin, end) by is_left that also gathers both sides' bounds and centroid bounds, so each
  // primitive is read once. Returns the first index of the right side.
  template <typename IsLeft>
  uint32_t partition(uint32_t begin, uint32_t end, IsLeft&& is_left, Box& lb, Box& lcb, Box& rb, Box& rcb) {
    BuildPrim* p = prims_.data();
    uint32_t i = begin, j = end;  // [begin, i) is left, [j, end) is right
    for (;;) {
      while (i < j && is_left(p[i])) add(p[i++], lb, lcb);
      while (i < j && !is_left(p[j - 1])) add(p[--j], rb, rcb);
      if (i >= j) return i;
      std::swap(p[i], p[j - 1]);  // p[i] belonged right and p[j - 1] left; they are now in place
      add(p[i++], lb, lcb);
      add(p[--j], rb, rcb);
    }
  }

  void make_leaf(uint32_t node, uint32_t begin, uint32_t end, const Box& b, uint32_t depth) {
    if (!cls_.empty()) {
      // Mixed classes: separate them first (one class per side, recursively).
      const uint8_t c0 = cls_[prims_[begin].id()];
      Box lb, lcb, rb, rcb;
      const uint32_t mid = partition(
          begin, end, [&](const BuildPrim& p) { return cls_[p.id()] == c0; }, lb, lcb, rb, rcb);
      if (mid != end) {
        const uint32_t c = next_.fetch_add(2, std::memory_order_relaxed);
        write_node(node, b, c, 0);
        make_leaf(c, begin, mid, lb, depth + 1);
        make_leaf(c + 1, mid, end, rb, depth + 1);
        return;
      }
    }
    write_node(node, b, begin, end - begin);
  }

  void write_node(uint32_t node, const Box& b, uint32_t offset, uint32_t count) {
    const Bounds3f x = b.bounds();
    nodes_[node] = BvhNode{x.lo, offset, x.hi, count};
  }

  void build(uint32_t node, uint32_t begin, uint32_t end, const Box& b, const Box& cb, uint32_t depth) {
    const uint32_t n = end - begin;
    if (n <= 1 || depth >= kMaxDepth) return make_leaf(node, begin, end, b, depth);
    // Any split costs at least traversal_cost, so when that alone exceeds the leaf's cost (e.g. up to one SIMD
    // block of primitives) the SAH answer is known without binning.
    if (n <= opt_.max_leaf_size && opt_.traversal_cost >= opt_.intersection_cost * leaf_cost(n))
      return make_leaf(node, begin, end, b, depth);

    // Best binned split over all three axes. Small nodes use fewer bins (no more than primitives): the sweep
    // over empty bins would cost more than the binning itself.
    const float area = b.half_area();
    int best_axis = -1, best_k = -1;
    float best_cost = kInfinity;
    const int nb = std::min(nb_, std::max(kMinSmallNodeBins, int(n)));
    const BinMapping map(cb, nb);
    if (area > 0.0f) {
      BinSet bins(nb);
      bin(begin, end, map, bins);
      for (int a = 0; a < 3; ++a) {
        if (!map.splittable(a)) continue;
        // Right-to-left sweep: area * cost of everything right of each plane.
        std::array<float, kMaxBins> right_cost;
        Box acc;
        uint32_t cnt = 0;
        for (int k = nb - 1; k > 0; --k) {
          acc.extend(Box{bins.box[a][k].lo, bins.box[a][k].hi});
          cnt += bins.count[a][k];
          right_cost[k - 1] = acc.half_area() * leaf_cost(cnt);
        }
        acc = Box();
        cnt = 0;
        for (int k = 0; k < nb - 1; ++k) {
          acc.extend(Box{bins.box[a][k].lo, bins.box[a][k].hi});
          cnt += bins.count[a][k];
          if (cnt == 0 || cnt == n) continue;
          const float cost = acc.half_area() * leaf_cost(cnt) + right_cost[k];
          if (cost < best_cost) {
            best_cost = cost;
            best_axis = a;
            best_k = k;
          }
        }
      }
      if (best_axis >= 0) best_cost = opt_.traversal_cost + opt_.intersection_cost * best_cost / area;
    }

    const float cost_as_leaf = opt_.intersection_cost * leaf_cost(n);
    uint32_t mid;
    Box lb, lcb, rb, rcb;
    if (best_axis >= 0 && (n > opt_.max_leaf_size || best_cost < cost_as_leaf)) {
      const int axis = best_axis, k = best_k;
      mid = partition(
          begin, end, [&](const BuildPrim& p) { return map(p.centroid2(), axis) <= k; }, lb, lcb, rb, rcb);
    } else if (n <= opt_.max_leaf_size) {
      return make_leaf(node, begin, end, b, depth);
    } else {
      // Too many primitives whose centroids coincide (or a flat node): split the range in the middle.
      mid = begin + n / 2;
      for (uint32_t i = begin; i < end; ++i) i < mid ? add(prims_[i], lb, lcb) : add(prims_[i], rb, rcb);
    }

    const uint32_t c = next_.fetch_add(2, std::memory_order_relaxed);
    write_node(node, b, c, 0);
    auto left = [&] { build(c, begin, mid, lb, lcb, depth + 1); };
    auto right = [&] { build(c + 1, mid, end, rb, rcb, depth + 1); };
    if (n >= kParallelSubtreeThreshold) {
      tbb::parallel_invoke(left, right);
    } else {
      left();
      right();
    }
  }

  // Depth-first order: each sibling pair is followed by the left child's subtree. Deterministic, whatever order
  // the parallel build allocated nodes in, and keeps a subtree's nodes together in memory.
  void relayout() {
    out_.nodes.assign(next_.load(), BvhNode{});
    uint32_t next = 2;
    place(kBvhRoot, kBvhRoot, next);
    out_.nodes.resize(std::max<uint32_t>(next, 2));
    // Unused padding node: an empty box no ray can enter.
    out_.nodes[1] = BvhNode{Vec3f(kInfinity), 0, Vec3f(-kInfinity), 0};
  }

  void place(uint32_t from, uint32_t to, uint32_t& next) {
    BvhNode nd = nodes_[from];
    if (!nd.is_leaf()) {
      const uint32_t c = next;
      next += 2;
      const uint32_t old = nd.offset;
      nd.offset = c;
      out_.nodes[to] = nd;
      place(old, c, next);
      place(old + 1, c + 1, next);
      return;
    }
    out_.nodes[to] = nd;
  }
};

}  // namespace

BvhBuildResult build_bvh(std::span<const Bounds3f> prim_bounds, const BvhBuildOptions& options,
                         std::span<const uint8_t> prim_class) {
  BvhBuildResult out;
  if (prim_bounds.empty()) {
    // A leaf with no primitives under an empty box.
    out.nodes.assign(2, BvhNode{Vec3f(kInfinity), 0, Vec3f(-kInfinity), 0});
    return out;
  }
  Builder(prim_bounds, prim_class, options, out).run();
  return out;
}

BvhTreeStats bvh_tree_stats(std::span<const BvhNode> nodes, const BvhBuildOptions& options) {
  BvhTreeStats s;
  if (nodes.empty()) return s;
  const float root_area = nodes[kBvhRoot].bounds().surface_area();
  struct Item {
    uint32_t node, depth;
  };
  std::vector<Item> stack{{kBvhRoot, 0}};
  double cost = 0;
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    const BvhNode& nd = nodes[it.node];
    const double rel = root_area > 0.0f ? double(nd.bounds().surface_area()) / root_area : 1.0;
    ++s.nodes;
    s.max_depth = std::max<size_t>(s.max_depth, it.depth);
    if (nd.is_leaf() || (it.node == kBvhRoot && nodes.size() == 2)) {
      ++s.leaves;
      s.primitives += nd.count;
      if (s.leaf_size_histogram.size() <= nd.count) s.leaf_size_histogram.resize(nd.count + 1, 0);
      ++s.leaf_size_histogram[nd.count];
      const uint32_t blk = std::max<uint32_t>(1, options.leaf_block);
      cost += rel * options.intersection_cost * double((nd.count + blk - 1) / blk);
    } else {
      cost += rel * options.traversal_cost;
      stack.push_back({nd.offset, it.depth + 1});
      stack.push_back({nd.offset + 1, it.depth + 1});
    }
  }
  s.sah_cost = cost;
  return s;
}

}  // namespace kiln
