#include "lights/light_tree.h"

#include <algorithm>
#include <bit>

namespace kiln {
namespace {

// Candidate split positions per axis: centroids are binned into this many buckets.
constexpr int kSplitBuckets = 12;

// The orientation measure of Conty Estevez & Kulla: the solid angle of emission directions a cone of normals
// (theta_o) with its spread (theta_e) covers, weighted by the cosine falloff.
float orientation_measure(const LightBounds& b) {
  const float theta_o = safe_acos(b.cos_theta_o), theta_e = safe_acos(b.cos_theta_e);
  const float theta_w = std::min(theta_o + theta_e, kPi);
  const float sin_o = safe_sqrt(1.0f - b.cos_theta_o * b.cos_theta_o);
  return 2.0f * kPi * (1.0f - b.cos_theta_o) +
         0.5f * kPi * (2.0f * theta_w * sin_o - std::cos(theta_o - 2.0f * theta_w) - 2.0f * theta_o * sin_o +
                       b.cos_theta_o);
}

// Surface area, or for boxes without area (point lights in a row) the squared diagonal.
double box_measure(const Bounds3f& b) {
  const Vec3f d = b.diagonal();
  const double x = d.x, y = d.y, z = d.z;
  const double area = 2.0 * (x * y + y * z + z * x);
  return area > 0.0 ? area : x * x + y * y + z * z;
}

// One side of a split: its emitters' power, spread of directions and size; splits along the parent's short axes
// cost more (the paper's regularisation), so thin boxes are not cut into thinner ones.
// In double: phi x area overflows a float in scenes of large extent.
double side_cost(const LightBounds& b, const Bounds3f& parent, int dim) {
  const Vec3f d = parent.diagonal();
  const double k_r = double(max_component(d)) / double(d[dim]);
  return double(b.phi) * double(orientation_measure(b)) * box_measure(b.box) * k_r;
}

int bucket_of(float c, float lo, float hi) {
  const int b = int(float(kSplitBuckets) * ((c - lo) / (hi - lo)));
  return std::clamp(b, 0, kSplitBuckets - 1);
}

int ceil_log2(size_t n) { return n <= 1 ? 0 : int(std::bit_width(n - 1)); }

// The weights of a node's children at (p, n), whose shares w[k] / sum are the probabilities of choosing them:
// their importances, or, where no child can light p (bounds are looser than their children's, so a walk can get
// there), their power, so that the walk always ends at a leaf and the probabilities of all leaves sum to 1 (the
// leaf it ends at lights p with nothing, as a failed sample would). Shared by sample() and pmf() so both multiply
// exactly the same numbers.
float child_weights(const ImportanceBounds4& child, Vec3f p, Vec3f n, float (&w)[4]) {
  importance4(child, p, n, w);
  float sum = (w[0] + w[1]) + (w[2] + w[3]);
  if (sum > 0.0f && sum < kInfinity) return sum;
  if (sum == kInfinity) {  // a point at a light: the infinite ones alone
    for (float& x : w) x = x == kInfinity ? 1.0f : 0.0f;
  } else {
    for (int k = 0; k < 4; ++k) w[k] = child.phi[k];
  }
  return (w[0] + w[1]) + (w[2] + w[3]);
}

}  // namespace

LightTree::LightTree(std::vector<EmitterBounds> emitters, size_t light_count, int max_depth)
    : first_slot_(light_count, kNoSlot), max_depth_(std::clamp(max_depth, 1, kMaxLightTreeDepth)) {
  slots_.resize(emitters.size());
  std::vector<BuildItem> items;
  items.reserve(emitters.size());
  for (size_t i = 0; i < emitters.size(); ++i) {
    const EmitterBounds& e = emitters[i];
    slots_[i].light = e.light;
    slots_[i].part = e.part;
    if (e.light < light_count && first_slot_[e.light] == kNoSlot) first_slot_[e.light] = uint32_t(i);
    if (e.bounds.phi > 0.0f && std::isfinite(e.bounds.phi) && !e.bounds.box.empty())
      items.push_back({uint32_t(i), e.bounds, e.bounds.box.center()});
  }
  leaves_ = items.size();
  if (items.empty()) return;
  nodes_.reserve(items.size() / 2 + 1);
  root_ = build(items, 0, items.size(), 0, 0).ref;
}

LightTree::Built LightTree::leaf(const BuildItem& item, uint64_t trail, int depth) {
  Slot& s = slots_[item.slot];
  s.trail = trail;
  s.depth = depth;
  depth_ = std::max(depth_, depth);
  return {kLeafBit | item.slot, item.bounds};
}

LightTree::Built LightTree::build(std::vector<BuildItem>& items, size_t begin, size_t end, uint64_t trail, int depth) {
  if (end - begin == 1) return leaf(items[begin], trail, depth);
  // Two levels of two-way splits make the (up to) four children.
  size_t bounds[5] = {begin, 0, 0, 0, 0};
  int n = 0;
  const size_t mid = split(items, begin, end, 2 * depth);
  for (const auto& [b, e] : {std::pair{begin, mid}, std::pair{mid, end}}) {
    if (e - b >= 2) {
      bounds[++n] = split(items, b, e, 2 * depth + 1);
    }
    bounds[++n] = e;
  }
  const uint32_t index = uint32_t(nodes_.size());
  nodes_.emplace_back();
  LightBounds all;
  Node node;
  for (int k = 0; k < n; ++k) {
    const uint64_t child_trail = trail | (uint64_t(k) << (2 * depth));
    const Built c = bounds[k + 1] - bounds[k] == 1 ? leaf(items[bounds[k]], child_trail, depth + 1)
                                                   : build(items, bounds[k], bounds[k + 1], child_trail, depth + 1);
    node.child.set(k, importance_bounds(c.bounds));
    node.next[k] = c.ref;
    all = merge(all, c.bounds);
  }
  nodes_[index] = node;
  return {index, all};
}

size_t LightTree::split(std::vector<BuildItem>& items, size_t begin, size_t end, int split_depth) const {
  Bounds3f box, centroids;
  for (size_t i = begin; i < end; ++i) {
    box.extend(items[i].bounds.box);
    centroids.extend(items[i].centroid);
  }
  const auto first = items.begin() + std::ptrdiff_t(begin), last = items.begin() + std::ptrdiff_t(end);
  const auto median_split = [&] {
    const int dim = max_dimension(centroids.diagonal());
    const auto mid = first + std::ptrdiff_t((end - begin) / 2);
    std::nth_element(first, mid, last, [&](const BuildItem& a, const BuildItem& b) { return a.centroid[dim] < b.centroid[dim]; });
    return size_t(mid - items.begin());
  };
  // Halving from here on still ends within the depth limit (two splits per level).
  if (split_depth + ceil_log2(end - begin) >= 2 * max_depth_) return median_split();

  double best_cost = std::numeric_limits<double>::infinity();
  int best_dim = -1, best_bucket = -1;
  for (int dim = 0; dim < 3; ++dim) {
    const float lo = centroids.lo[dim], hi = centroids.hi[dim];
    if (!(hi > lo)) continue;
    LightBounds bucket[kSplitBuckets];
    for (size_t i = begin; i < end; ++i) {
      LightBounds& b = bucket[bucket_of(items[i].centroid[dim], lo, hi)];
      b = merge(b, items[i].bounds);
    }
    LightBounds above[kSplitBuckets];  // above[k]: buckets k.. together
    above[kSplitBuckets - 1] = bucket[kSplitBuckets - 1];
    for (int k = kSplitBuckets - 2; k >= 0; --k) above[k] = merge(bucket[k], above[k + 1]);
    LightBounds below;
    for (int k = 0; k + 1 < kSplitBuckets; ++k) {
      below = merge(below, bucket[k]);
      if (!(below.phi > 0.0f) || !(above[k + 1].phi > 0.0f)) continue;
      const double cost = side_cost(below, box, dim) + side_cost(above[k + 1], box, dim);
      if (cost < best_cost) {
        best_cost = cost;
        best_dim = dim;
        best_bucket = k;
      }
    }
  }
  if (best_dim < 0) return median_split();
  const float lo = centroids.lo[best_dim], hi = centroids.hi[best_dim];
  const auto mid = std::partition(first, last, [&](const BuildItem& it) {
    return bucket_of(it.centroid[best_dim], lo, hi) <= best_bucket;
  });
  if (mid == first || mid == last) return median_split();
  return size_t(mid - items.begin());
}

std::optional<TreeChoice> LightTree::sample(Vec3f p, Vec3f n, float u) const {
  if (empty()) return std::nullopt;
  uint32_t ref = root_;
  float pmf = 1.0f;
  while (!(ref & kLeafBit)) {
    const Node& node = nodes_[ref];
    float w[4];
    const float sum = child_weights(node.child, p, n, w);
    // The child whose part of [0, sum) holds u * sum: the number of parts that end at or below it (parts of
    // weight 0 end where the previous one does, so they are never chosen; should rounding put u * sum past them
    // all, the last one with weight). u becomes the position within that part for the next level.
    const float target = u * sum;
    const float start[4] = {0.0f, w[0], w[0] + w[1], (w[0] + w[1]) + w[2]};
    int c = int(target >= start[1]) + int(target >= start[2]) + int(target >= start[3]);
    while (!(w[c] > 0.0f)) --c;
    u = std::clamp((target - start[c]) / w[c], 0.0f, kOneMinusEpsilon);
    pmf *= w[c] / sum;
    ref = node.next[c];
  }
  const Slot& s = slots_[ref & ~kLeafBit];
  return TreeChoice{s.light, s.part, pmf};
}

uint32_t LightTree::slot_of(uint32_t light, uint32_t part) const {
  if (light >= first_slot_.size() || first_slot_[light] == kNoSlot) return kNoSlot;
  const size_t slot = size_t(first_slot_[light]) + (part == kWholeLight ? 0 : size_t(part));
  if (slot >= slots_.size() || slots_[slot].light != light || slots_[slot].part != part) return kNoSlot;
  return uint32_t(slot);
}

float LightTree::pmf(Vec3f p, Vec3f n, uint32_t light, uint32_t part) const {
  const uint32_t slot = slot_of(light, part);
  if (slot == kNoSlot || slots_[slot].depth < 0) return 0.0f;
  uint64_t trail = slots_[slot].trail;
  uint32_t ref = root_;
  float pmf = 1.0f;
  while (!(ref & kLeafBit)) {
    const Node& node = nodes_[ref];
    float w[4];
    const float sum = child_weights(node.child, p, n, w);
    const int c = int(trail & 3u);
    pmf *= w[c] / sum;
    ref = node.next[c];
    trail >>= 2;
  }
  return pmf;
}

size_t LightTree::bytes() const {
  return nodes_.capacity() * sizeof(Node) + slots_.capacity() * sizeof(Slot) + first_slot_.capacity() * sizeof(uint32_t);
}

}  // namespace kiln
