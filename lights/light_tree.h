// A bounding volume hierarchy over emitters (whole lights, or single triangles of mesh lights) with the bounds of
// lights/light_bounds.h at every node, for choosing one emitter in proportion to how much it may light a point
// (Conty Estevez & Kulla 2018; pbrt-v4's BVHLightSampler is the same design, with two children per node).
//
// Four children per node, whose importances at (p, n) one SIMD pass computes (importance4): sampling walks from the
// root, at each node choosing a child with probability proportional to its importance (by power where no child can
// light p); the product of those choices is the emitter's probability, and the probabilities of all emitters sum
// to 1. pmf() walks the same path to one emitter, steered by the emitter's trail (bits 2k, 2k+1: which child at
// depth k), so it returns exactly what sample() multiplies.
// Build: top-down, each node's emitters split in two and each half in two again, every split by buckets of
// centroids along one axis minimising phi x (orientation measure M_omega) x (box area) over both sides (the paper's
// cost), and at the median wherever the depth would otherwise pass the limit.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "lights/light_bounds.h"

namespace kiln {

inline constexpr int kMaxLightTreeDepth = 32;  // levels of 4-way choices: an emitter's trail is one 64-bit word

struct TreeChoice {
  uint32_t light = 0;
  uint32_t part = kWholeLight;
  float pmf = 0.0f;
};

class LightTree {
 public:
  LightTree() = default;
  // emitters: the parts of every bounded light, those of one light consecutive (append_emitter_bounds in light
  // order). Parts with phi <= 0 are kept out of the tree (never chosen).
  // max_depth (at most kMaxLightTreeDepth): no leaf deeper than this many levels.
  LightTree(std::vector<EmitterBounds> emitters, size_t light_count, int max_depth = kMaxLightTreeDepth);

  bool empty() const { return leaves_ == 0; }
  // The chosen emitter and its probability; empty only when the tree is. u in [0, 1).
  std::optional<TreeChoice> sample(Vec3f p, Vec3f n, float u) const;
  // Probability that sample(p, n, .) chooses part `part` (kWholeLight or a triangle) of light `light`; 0 for parts
  // the tree does not hold.
  float pmf(Vec3f p, Vec3f n, uint32_t light, uint32_t part) const;
  // True when the tree holds light `light` triangle by triangle.
  bool splits(uint32_t light) const {
    return light < first_slot_.size() && first_slot_[light] != kNoSlot && slots_[first_slot_[light]].part != kWholeLight;
  }

  size_t emitter_count() const { return leaves_; }
  size_t node_count() const { return nodes_.size(); }  // 4-wide interior nodes
  int depth() const { return depth_; }                 // levels of choices down to the deepest leaf
  size_t bytes() const;

 private:
  static constexpr uint32_t kNoSlot = 0xffffffffu;
  static constexpr uint32_t kLeafBit = 0x80000000u;
  // An interior node holds its children's bounds, so one node is read per level; unused lanes have phi 0.
  struct Node {
    ImportanceBounds4 child;
    uint32_t next[4] = {0, 0, 0, 0};  // interior node index, or kLeafBit | slot
  };
  struct Slot {
    uint32_t light = 0, part = kWholeLight;
    uint64_t trail = 0;
    int depth = -1;  // -1: not in the tree
  };
  struct BuildItem {
    uint32_t slot;
    LightBounds bounds;
    Vec3f centroid;
  };
  struct Built {
    uint32_t ref;  // node index or kLeafBit | slot
    LightBounds bounds;
  };

  Built build(std::vector<BuildItem>& items, size_t begin, size_t end, uint64_t trail, int depth);
  Built leaf(const BuildItem& item, uint64_t trail, int depth);
  // Splits [begin, end) in two; split_depth counts two-way splits from the root.
  size_t split(std::vector<BuildItem>& items, size_t begin, size_t end, int split_depth) const;
  uint32_t slot_of(uint32_t light, uint32_t part) const;

  std::vector<Node> nodes_;
  std::vector<Slot> slots_;             // one per emitter given, in the given order
  std::vector<uint32_t> first_slot_;    // per light: its first slot, or kNoSlot
  uint32_t root_ = 0;                   // nodes_[0], or kLeafBit | slot when the tree holds one emitter
  size_t leaves_ = 0;
  int depth_ = 0;
  int max_depth_ = kMaxLightTreeDepth;
};

}  // namespace kiln
