#include "renderer/accel/bvh_build.h"

#include <algorithm>
#include <array>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

namespace kiln {
namespace {

constexpr int kMinBins = 2;
constexpr int kMaxBins = 32;
constexpr uint32_t kParallelSubtreeThreshold = 4096;  // smaller subtrees are not worth a task
constexpr uint32_t kParallelBinThreshold = 32768;     // nodes this large bin their primitives in parallel
constexpr uint32_t kParallelBinGrain = 8192;
// Bounds the tree depth so fixed-size traversal stacks (kBvhMaxDepth entries) can never overflow.
constexpr uint32_t kMaxDepth = 60;

struct Bin {
  Bounds3f b;   // primitive bounds
  Bounds3f cb;  // centroid bounds
  uint32_t n = 0;
};

struct BinSet {
  std::array<std::array<Bin, kMaxBins>, 3> bins;
  void merge(const BinSet& o, int nb) {
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < nb; ++k) {
        bins[a][k].b.extend(o.bins[a][k].b);
        bins[a][k].cb.extend(o.bins[a][k].cb);
        bins[a][k].n += o.bins[a][k].n;
      }
  }
};

// Maps centroid coordinates of one node to bin indices; the partition uses the same mapping as the binning so
// both agree exactly on which side a primitive falls.
struct BinMapping {
  Vec3f lo, scale;
  int nb;
  BinMapping(const Bounds3f& cb, int bins) : lo(cb.lo), nb(bins) {
    const Vec3f ext = cb.diagonal();
    for (int a = 0; a < 3; ++a) scale[a] = ext[a] > 0.0f ? float(bins) / ext[a] : 0.0f;
  }
  int operator()(float c, int axis) const {
    const int k = int((c - lo[axis]) * scale[axis]);
    return std::clamp(k, 0, nb - 1);
  }
};

class Builder {
 public:
  Builder(std::span<const Bounds3f> pb, const BvhBuildOptions& opt, BvhBuildResult& out)
      : pb_(pb), opt_(opt), nb_(std::clamp(opt.bins_per_axis, kMinBins, kMaxBins)), out_(out) {}

  void run() {
    const uint32_t n = uint32_t(pb_.size());
    out_.order.resize(n);
    centroids_.resize(n);
    Bounds3f b, cb;
    for (uint32_t i = 0; i < n; ++i) {
      out_.order[i] = i;
      centroids_[i] = pb_[i].center();
      b.extend(pb_[i]);
      cb.extend(centroids_[i]);
    }
    nodes_.assign(std::max<size_t>(2, 2 * size_t(n)), BvhNode{});
    build(kBvhRoot, 0, n, b, cb, 0);
    relayout();
  }

 private:
  std::span<const Bounds3f> pb_;
  const BvhBuildOptions& opt_;
  int nb_;
  BvhBuildResult& out_;
  std::vector<Vec3f> centroids_;
  std::vector<BvhNode> nodes_;  // build order; relaid out depth-first into out_.nodes
  std::atomic<uint32_t> next_{2};

  void bin_range(uint32_t begin, uint32_t end, const BinMapping& map, BinSet& bins) const {
    for (uint32_t i = begin; i < end; ++i) {
      const uint32_t p = out_.order[i];
      const Vec3f c = centroids_[p];
      for (int a = 0; a < 3; ++a) {
        Bin& bin = bins.bins[a][map(c[a], a)];
        bin.b.extend(pb_[p]);
        bin.cb.extend(c);
        ++bin.n;
      }
    }
  }

  BinSet bin(uint32_t begin, uint32_t end, const BinMapping& map) const {
    if (end - begin < kParallelBinThreshold) {
      BinSet bins;
      bin_range(begin, end, map, bins);
      return bins;
    }
    return tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(begin, end, kParallelBinGrain), BinSet{},
        [&](const tbb::blocked_range<uint32_t>& r, BinSet acc) {
          bin_range(r.begin(), r.end(), map, acc);
          return acc;
        },
        [&](BinSet a, const BinSet& b) {
          a.merge(b, nb_);
          return a;
        });
  }

  void make_leaf(uint32_t node, uint32_t begin, uint32_t end, const Bounds3f& b) {
    nodes_[node] = BvhNode{b.lo, begin, b.hi, end - begin};
  }

  void build(uint32_t node, uint32_t begin, uint32_t end, const Bounds3f& b, const Bounds3f& cb, uint32_t depth) {
    const uint32_t n = end - begin;
    if (n <= 1 || depth >= kMaxDepth) return make_leaf(node, begin, end, b);

    // Best binned split over all three axes.
    const float area = b.surface_area();
    int best_axis = -1, best_k = -1;
    float best_cost = kInfinity;
    Bounds3f best_lb, best_lcb, best_rb, best_rcb;
    const BinMapping map(cb, nb_);
    if (area > 0.0f && max_component(cb.diagonal()) > 0.0f) {
      const BinSet bins = bin(begin, end, map);
      for (int a = 0; a < 3; ++a) {
        if (!(map.scale[a] > 0.0f)) continue;
        const auto& bs = bins.bins[a];
        // Right-to-left sweep: area * count of everything right of each plane.
        std::array<float, kMaxBins> right_cost{};
        Bounds3f acc;
        uint32_t cnt = 0;
        for (int k = nb_ - 1; k > 0; --k) {
          acc.extend(bs[k].b);
          cnt += bs[k].n;
          right_cost[k - 1] = acc.surface_area() * float(cnt);
        }
        acc = Bounds3f();
        cnt = 0;
        for (int k = 0; k < nb_ - 1; ++k) {
          acc.extend(bs[k].b);
          cnt += bs[k].n;
          if (cnt == 0 || cnt == n) continue;
          const float cost = acc.surface_area() * float(cnt) + right_cost[k];
          if (cost < best_cost) {
            best_cost = cost;
            best_axis = a;
            best_k = k;
          }
        }
      }
      if (best_axis >= 0) {
        for (int k = 0; k < nb_; ++k) {
          const Bin& bn = bins.bins[best_axis][k];
          (k <= best_k ? best_lb : best_rb).extend(bn.b);
          (k <= best_k ? best_lcb : best_rcb).extend(bn.cb);
        }
        best_cost = opt_.traversal_cost + opt_.intersection_cost * best_cost / area;
      }
    }

    const float leaf_cost = opt_.intersection_cost * float(n);
    uint32_t mid;
    if (best_axis >= 0 && (n > opt_.max_leaf_size || best_cost < leaf_cost)) {
      const int axis = best_axis, k = best_k;
      auto* first = out_.order.data();
      mid = uint32_t(std::partition(first + begin, first + end,
                                    [&](uint32_t p) { return map(centroids_[p][axis], axis) <= k; }) -
                     first);
    } else if (n <= opt_.max_leaf_size) {
      return make_leaf(node, begin, end, b);
    } else {
      // Too many primitives whose centroids coincide (or a flat node): split the range in the middle.
      mid = begin + n / 2;
      best_lb = best_lcb = best_rb = best_rcb = Bounds3f();
      for (uint32_t i = begin; i < end; ++i) {
        const uint32_t p = out_.order[i];
        (i < mid ? best_lb : best_rb).extend(pb_[p]);
        (i < mid ? best_lcb : best_rcb).extend(centroids_[p]);
      }
    }

    const uint32_t c = next_.fetch_add(2, std::memory_order_relaxed);
    nodes_[node] = BvhNode{b.lo, c, b.hi, 0};
    auto left = [&] { build(c, begin, mid, best_lb, best_lcb, depth + 1); };
    auto right = [&] { build(c + 1, mid, end, best_rb, best_rcb, depth + 1); };
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

BvhBuildResult build_bvh(std::span<const Bounds3f> prim_bounds, const BvhBuildOptions& options) {
  BvhBuildResult out;
  if (prim_bounds.empty()) {
    // A leaf with no primitives under an empty box.
    out.nodes.assign(2, BvhNode{Vec3f(kInfinity), 0, Vec3f(-kInfinity), 0});
    return out;
  }
  Builder(prim_bounds, options, out).run();
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
      cost += rel * options.intersection_cost * nd.count;
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
