#include "renderer/accel/bvh.h"

#include <immintrin.h>  // SSE2 only: part of the x86-64 baseline
#include <tbb/parallel_for.h>

#include <chrono>
#include <limits>

#include "renderer/accel/alpha.h"
#include "renderer/accel/object_ray.h"
#include "renderer/accel/quadric_intersect.h"
#include "renderer/accel/shape_bounds.h"
#include "renderer/accel/surface_point.h"
#include "renderer/accel/sphere_intersect.h"
#include "renderer/accel/traceable_ray.h"
#include "renderer/accel/tri4_intersect.h"
#include "renderer/accel/triangle_intersect.h"

namespace kiln {
namespace {

// A leaf primitive: the shape it belongs to and, in the low bits of prim, the triangle / sphere / instance / quadric
// index; the top three bits say which.
struct PrimRef {
  uint32_t shape;
  uint32_t prim;
};
constexpr uint32_t kKindShift = 29;
constexpr uint32_t kIndexMask = (1u << kKindShift) - 1;
// A moving world mesh is one primitive of the world tree (its swept box) with its own tree at time 0, like an
// instance's prototype; moving spheres and instances keep their kinds and move the ray back by their offset.
constexpr uint32_t kKindTriangle = 0, kKindSphere = 1, kKindInstance = 2, kKindMovingMesh = 3, kKindQuadric = 4;
inline uint32_t ref_kind(PrimRef r) { return r.prim >> kKindShift; }
inline uint32_t ref_index(PrimRef r) { return r.prim & kIndexMask; }

// Traversal layout: the binary SAH tree collapsed into a 4-wide tree whose node holds its four child boxes as
// SoA rows, so one ray is tested against all four with SSE. 128 bytes = two cache lines.
// A child reference: an interior node index, or a leaf: kLeafBit, kOtherBit for a leaf of spheres/instances
// (whose index is the first of Tree::refs rather than the first Tri4 packet), item count in bits 32-61.
using ChildRef = uint64_t;
constexpr ChildRef kLeafBit = 1ull << 63;
constexpr ChildRef kOtherBit = 1ull << 62;
constexpr int kCountShift = 32;
constexpr ChildRef kCountMask = (1ull << 30) - 1;
constexpr ChildRef kEmptyChild = kLeafBit;  // a leaf with no items (its box is empty too)
inline ChildRef make_leaf_ref(bool other, uint32_t first, uint64_t count) {
  return kLeafBit | (other ? kOtherBit : 0) | (std::min<uint64_t>(count, kCountMask) << kCountShift) | first;
}
inline uint32_t ref_first(ChildRef r) { return uint32_t(r); }
inline uint32_t ref_count(ChildRef r) { return uint32_t((r >> kCountShift) & kCountMask); }

struct alignas(64) Node4 {
  float b[6][4];  // row 2a: lower bound on axis a, row 2a+1: upper bound; one column per child
  ChildRef child[4];
};
static_assert(sizeof(Node4) == 128);

// Slab distances are rounded; enlarging the far distance by 2 gamma(3) makes the box test conservative so a
// triangle lying exactly on a box face is never culled (Ize 2013, "Robust BVH Ray Traversal").
constexpr float kSlabRobustScale = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);
// Direction components below this are clamped so 1/d stays finite and 0 * inf never produces NaN.
constexpr float kMinDirComponent = 1e-30f;
// Traversal stack entries: at most 3 pushes per level of a 4-wide tree no deeper than the binary tree (< 64).
constexpr int kStackSize = 192;

struct Tree {
  std::vector<Node4, tbb::cache_aligned_allocator<Node4>> nodes;
  std::vector<Tri4, tbb::cache_aligned_allocator<Tri4>> packets;
  std::vector<PrimRef> refs;  // leaf order
  ChildRef root = kEmptyChild;
  BvhTreeStats binary_stats;
  bool empty() const { return root == kEmptyChild; }
  size_t bytes() const {
    return nodes.capacity() * sizeof(Node4) + packets.capacity() * sizeof(Tri4) + refs.capacity() * sizeof(PrimRef);
  }
};

struct TravRay {
  Vec3f o, d, inv_d;
  WatertightRay wr;
  float tmin;
  float time;
  int near[3], far[3];  // rows of Node4::b holding the entry / exit plane on each axis
  const Ray* world;     // the query's world-space ray (the alpha hash's), also inside instances and moving meshes
  TravRay(const Ray& r, const Ray* world_ray)
      : o(r.o), d(r.d), wr(make_watertight_ray(r)), tmin(r.tmin), time(r.time), world(world_ray) {
    for (int a = 0; a < 3; ++a) {
      const float c = std::abs(d[a]) >= kMinDirComponent ? d[a] : std::copysign(kMinDirComponent, d[a]);
      inv_d[a] = 1.0f / c;
      near[a] = 2 * a + (inv_d[a] < 0.0f ? 1 : 0);
      far[a] = 2 * a + (inv_d[a] < 0.0f ? 0 : 1);
    }
  }
};

struct Closest {
  float t;
  uint32_t shape = kInvalidId, prim = kInvalidId;
  float b1 = 0, b2 = 0;
};

// Collapses the binary tree into Node4s (pre-order, so a node's children follow it) and lays leaf primitives out
// as Tri4 packets in the same order. Nodes are made in one sequential pass; packets, whose vertex gathers are
// the expensive part, are only numbered there and filled in parallel afterwards.
class Collapser {
 public:
  Collapser(const BvhBuildResult& bin, Tree& out) : bin_(bin), out_(out) {}
  template <typename VertexOf>
  void run(VertexOf& vertex_of) {
    out_.root = bin_.nodes[kBvhRoot].is_leaf() ? leaf_ref(kBvhRoot) : interior(kBvhRoot);
    out_.packets.resize(packet_count_);
    tbb::parallel_for(size_t(0), leaves_.size(), [&](size_t l) { fill_packets(leaves_[l], vertex_of); });
  }

 private:
  struct PendingLeaf {
    uint32_t bin_node, first_packet;
  };
  const BvhBuildResult& bin_;
  Tree& out_;
  uint32_t packet_count_ = 0;
  std::vector<PendingLeaf> leaves_;

  ChildRef leaf_ref(uint32_t bin_node) {
    const BvhNode& n = bin_.nodes[bin_node];
    if (n.count == 0) return kEmptyChild;
    if (ref_kind(out_.refs[n.offset]) != kKindTriangle) return make_leaf_ref(true, n.offset, n.count);
    const uint32_t first = packet_count_, count = (n.count + kWidth - 1) / kWidth;
    packet_count_ += count;
    leaves_.push_back({bin_node, first});
    return make_leaf_ref(false, first, count);
  }

  template <typename VertexOf>
  void fill_packets(const PendingLeaf& leaf, VertexOf& vertex_of) const {
    const BvhNode& n = bin_.nodes[leaf.bin_node];
    for (uint32_t i = 0; i < n.count; i += kWidth) {
      Tri4& p = out_.packets[leaf.first_packet + i / kWidth];
      for (int lane = 0; lane < kWidth; ++lane) {
        const bool used = i + uint32_t(lane) < n.count;
        const uint32_t slot = n.offset + i + uint32_t(lane);
        p.slot[lane] = used ? slot : kInvalidId;
        for (int k = 0; k < 3; ++k) {
          const Vec3f v = used ? vertex_of(out_.refs[slot], k) : Vec3f(std::numeric_limits<float>::quiet_NaN());
          for (int a = 0; a < 3; ++a) p.v[k][a][lane] = v[a];
        }
      }
    }
  }

  ChildRef interior(uint32_t bin_node) {
    // Open up to four children, always expanding the largest interior one (the likeliest to be visited).
    uint32_t kids[kWidth] = {bin_.nodes[bin_node].offset, bin_.nodes[bin_node].offset + 1, 0, 0};
    int n = 2;
    while (n < kWidth) {
      int best = -1;
      float best_area = -1.0f;
      for (int i = 0; i < n; ++i) {
        const BvhNode& c = bin_.nodes[kids[i]];
        if (!c.is_leaf() && c.bounds().surface_area() > best_area) {
          best = i;
          best_area = c.bounds().surface_area();
        }
      }
      if (best < 0) break;
      const uint32_t open = kids[best];
      kids[best] = bin_.nodes[open].offset;
      kids[n++] = bin_.nodes[open].offset + 1;
    }
    const uint32_t index = uint32_t(out_.nodes.size());
    out_.nodes.emplace_back();
    Node4 node;
    for (int i = 0; i < kWidth; ++i) {
      const bool used = i < n;
      const Bounds3f b = used ? bin_.nodes[kids[i]].bounds() : Bounds3f();
      for (int a = 0; a < 3; ++a) {
        node.b[2 * a][i] = b.lo[a];
        node.b[2 * a + 1][i] = b.hi[a];
      }
      node.child[i] = !used ? kEmptyChild : bin_.nodes[kids[i]].is_leaf() ? leaf_ref(kids[i]) : interior(kids[i]);
    }
    out_.nodes[index] = node;
    return index;
  }
};

}  // namespace

struct Bvh::Impl {
  const WorldGeometry& g;
  BvhOptions options;
  Tree world;
  std::vector<Tree> prototypes;  // empty trees for prototypes no instance uses
  std::vector<Tree> moving_meshes;  // per world mesh: its own tree when the mesh moves, else empty
  std::vector<Transform> instance_to_object;
  std::vector<Transform> sphere_to_object;
  std::vector<uint8_t> sphere_transformed;
  std::vector<Transform> quadric_to_object;
  BvhStats stats;

  Impl(const WorldGeometry& geometry, const BvhOptions& opt) : g(geometry), options(opt) {}

  // Builds over bounds (prims described by refs), keeps refs in leaf order and packs triangle leaves, whose
  // vertices come from mesh_of(ref).
  template <typename MeshOf>
  Tree make_tree(const std::vector<Bounds3f>& bounds, const std::vector<PrimRef>& refs, MeshOf&& mesh_of) const {
    std::vector<uint8_t> cls(refs.size());
    bool mixed = false;
    for (size_t i = 0; i < refs.size(); ++i) {
      cls[i] = uint8_t(ref_kind(refs[i]));
      mixed |= cls[i] != cls[0];
    }
    const BvhBuildResult built =
        build_bvh(bounds, options.build, mixed ? std::span<const uint8_t>(cls) : std::span<const uint8_t>());
    Tree t;
    t.binary_stats = bvh_tree_stats(built.nodes, options.build);
    if (built.order.empty()) return t;
    t.refs.resize(built.order.size());
    tbb::parallel_for(size_t(0), built.order.size(), [&](size_t i) { t.refs[i] = refs[built.order[i]]; });
    // The node count is bounded by the binary interior nodes, and trimmed after collapsing.
    t.nodes.reserve(built.nodes.size() / 2 + 1);
    auto vertex_of = [&](PrimRef r, int k) { return mesh_of(r).vertex(ref_index(r), k); };
    Collapser(built, t).run(vertex_of);
    t.nodes.shrink_to_fit();
    return t;
  }

  // Triangle-only tree over one prototype mesh (object space).
  Tree build_mesh_tree(const TriangleMesh& m) const {
    const size_t n = m.triangle_count();
    std::vector<Bounds3f> bounds(n);
    std::vector<PrimRef> refs(n);
    tbb::parallel_for(size_t(0), n, [&](size_t t) {
      Bounds3f b(m.vertex(t, 0));
      b.extend(m.vertex(t, 1));
      b.extend(m.vertex(t, 2));
      bounds[t] = b;
      refs[t] = {0, uint32_t(t)};
    });
    return make_tree(bounds, refs, [&](PrimRef) -> const TriangleMesh& { return m; });
  }

  void build() {
    const auto start = std::chrono::steady_clock::now();
    std::vector<uint8_t> used(g.prototypes.size(), 0);
    for (const MeshInstance& inst : g.instances) used[inst.prototype] = 1;
    prototypes.resize(g.prototypes.size());
    for (size_t p = 0; p < g.prototypes.size(); ++p)
      if (used[p]) prototypes[p] = build_mesh_tree(g.prototypes[p]);
    instance_to_object.reserve(g.instances.size());
    for (const MeshInstance& inst : g.instances) instance_to_object.push_back(inst.to_world.inverse());
    for (const SphereShape& s : g.spheres) {
      sphere_to_object.push_back(s.to_world.inverse());
      sphere_transformed.push_back(!s.to_world.is_identity());
    }
    for (const QuadricShape& q : g.quadrics) quadric_to_object.push_back(q.to_world.inverse());
    moving_meshes.resize(g.meshes.size());
    for (const Shape& s : g.shapes)
      if (s.kind == ShapeKind::Mesh && s.moving()) moving_meshes[s.index] = build_mesh_tree(g.meshes[s.index]);

    // World primitives: triangles of static world meshes (in shape order), then spheres, then instances, then
    // moving meshes, then quadrics.
    std::vector<size_t> first_tri(g.shapes.size() + 1, 0);
    for (size_t i = 0; i < g.shapes.size(); ++i) {
      const Shape& s = g.shapes[i];
      const bool flat = s.kind == ShapeKind::Mesh && !s.moving();
      first_tri[i + 1] = first_tri[i] + (flat ? g.meshes[s.index].triangle_count() : 0);
    }
    std::vector<Bounds3f> bounds(first_tri.back());
    std::vector<PrimRef> refs(first_tri.back());
    for (uint32_t i = 0; i < g.shapes.size(); ++i) {
      const Shape& s = g.shapes[i];
      if (s.kind != ShapeKind::Mesh || s.moving()) continue;
      const TriangleMesh& m = g.meshes[s.index];
      tbb::parallel_for(size_t(0), m.triangle_count(), [&, i](size_t t) {
        Bounds3f b(m.vertex(t, 0));
        b.extend(m.vertex(t, 1));
        b.extend(m.vertex(t, 2));
        bounds[first_tri[i] + t] = b;
        refs[first_tri[i] + t] = {i, uint32_t(t)};
      });
    }
    for (uint32_t i = 0; i < g.shapes.size(); ++i) {
      const Shape& s = g.shapes[i];
      if (s.kind == ShapeKind::Sphere) {
        bounds.push_back(shape_world_bounds(g, s));
        refs.push_back({i, (kKindSphere << kKindShift) | s.index});
      }
    }
    for (uint32_t i = 0; i < g.shapes.size(); ++i) {
      const Shape& s = g.shapes[i];
      if (s.kind == ShapeKind::Instance && !prototypes[g.instances[s.index].prototype].empty()) {
        bounds.push_back(shape_world_bounds(g, s));
        refs.push_back({i, (kKindInstance << kKindShift) | s.index});
      }
    }
    for (uint32_t i = 0; i < g.shapes.size(); ++i) {
      const Shape& s = g.shapes[i];
      if (s.kind == ShapeKind::Mesh && s.moving() && !moving_meshes[s.index].empty()) {
        bounds.push_back(shape_world_bounds(g, s));
        refs.push_back({i, (kKindMovingMesh << kKindShift) | s.index});
      }
    }
    for (uint32_t i = 0; i < g.shapes.size(); ++i) {
      const Shape& s = g.shapes[i];
      if (s.kind == ShapeKind::Quadric) {
        bounds.push_back(shape_world_bounds(g, s));
        refs.push_back({i, (kKindQuadric << kKindShift) | s.index});
      }
    }
    if (options.debug_drop_primitive && *options.debug_drop_primitive < refs.size()) {
      bounds.erase(bounds.begin() + ptrdiff_t(*options.debug_drop_primitive));
      refs.erase(refs.begin() + ptrdiff_t(*options.debug_drop_primitive));
    }
    world =
        make_tree(bounds, refs, [&](PrimRef r) -> const TriangleMesh& { return g.meshes[g.shapes[r.shape].index]; });
    stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    stats.world = world.binary_stats;
    stats.wide_nodes = world.nodes.size();
    stats.bytes = world.bytes() + (instance_to_object.capacity() + sphere_to_object.capacity() +
                                   quadric_to_object.capacity()) *
                                      sizeof(Transform);
    for (const Tree& t : moving_meshes) stats.bytes += t.bytes();
    for (const Tree& t : prototypes) {
      if (t.empty()) continue;
      ++stats.prototype_trees;
      stats.prototype_nodes += t.nodes.size();
      stats.bytes += t.bytes();
    }
  }

  // Closest hit (kAny = false) or any hit (kAny = true) in tree with t in [ray.tmin, tmax]; tmax shrinks as
  // closer hits are found. shape_override names the instance shape when traversing a prototype tree. kAlpha: the
  // scene has alpha cut-outs (compiled out of the triangle leaves of scenes without).
  template <bool kAny, bool kAlpha>
  bool traverse(const Tree& tree, const TravRay& r, float& tmax, Closest& best, uint32_t shape_override) const {
    if (tree.empty()) return false;
    struct Entry {
      ChildRef ref;
      float tnear;
    };
    Entry stack[kStackSize];
    int sp = 0;
    stack[sp++] = {tree.root, r.tmin};
    bool found = false;
    const __m128 ox = _mm_set1_ps(r.o.x), oy = _mm_set1_ps(r.o.y), oz = _mm_set1_ps(r.o.z);
    const __m128 ix = _mm_set1_ps(r.inv_d.x), iy = _mm_set1_ps(r.inv_d.y), iz = _mm_set1_ps(r.inv_d.z);
    const __m128 tminv = _mm_set1_ps(r.tmin), robust = _mm_set1_ps(kSlabRobustScale);
    const Node4* nodes = tree.nodes.data();
    while (sp > 0) {
      const Entry e = stack[--sp];
      if (e.tnear > tmax) continue;  // a closer hit was found since this subtree was pushed
      ChildRef ref = e.ref;
      bool descend = true;
      while (!(ref & kLeafBit)) {
        const Node4& n = nodes[ref];
        const __m128 tx0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.b[r.near[0]]), ox), ix);
        const __m128 ty0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.b[r.near[1]]), oy), iy);
        const __m128 tz0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.b[r.near[2]]), oz), iz);
        const __m128 tx1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.b[r.far[0]]), ox), ix);
        const __m128 ty1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.b[r.far[1]]), oy), iy);
        const __m128 tz1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.b[r.far[2]]), oz), iz);
        const __m128 tn = _mm_max_ps(_mm_max_ps(tx0, ty0), _mm_max_ps(tz0, tminv));
        const __m128 tf = _mm_min_ps(_mm_mul_ps(_mm_min_ps(_mm_min_ps(tx1, ty1), tz1), robust), _mm_set1_ps(tmax));
        int mask = _mm_movemask_ps(_mm_cmple_ps(tn, tf));
        if (!mask) {
          descend = false;
          break;
        }
        alignas(16) float dist[4];
        _mm_store_ps(dist, tn);
        int i = __builtin_ctz(unsigned(mask));
        mask &= mask - 1;
        if (!mask) {  // one child hit: no stack traffic
          ref = n.child[i];
          continue;
        }
        // Two to four children hit: push all but the nearest, farthest first, so they pop near to far.
        Entry hits[4];
        int nh = 0;
        hits[nh++] = {n.child[i], dist[i]};
        while (mask) {
          i = __builtin_ctz(unsigned(mask));
          mask &= mask - 1;
          Entry h{n.child[i], dist[i]};
          int k = nh++;
          for (; k > 0 && hits[k - 1].tnear > h.tnear; --k) hits[k] = hits[k - 1];
          hits[k] = h;
        }
        for (int k = nh - 1; k >= 1; --k) stack[sp++] = hits[k];
        ref = hits[0].ref;
      }
      if (!descend) continue;
      if (leaf<kAny, kAlpha>(tree, ref, r, tmax, best, shape_override)) {
        if constexpr (kAny) return true;
        found = true;
      }
    }
    return found;
  }

  template <bool kAny, bool kAlpha>
  bool leaf(const Tree& tree, ChildRef ref, const TravRay& r, float& tmax, Closest& best,
            uint32_t shape_override) const {
    const uint32_t first = ref_first(ref), count = ref_count(ref);
    bool found = false;
    if (ref & kOtherBit) [[unlikely]] {
      for (uint32_t i = first; i < first + count; ++i) {
        if (other_prim<kAny, kAlpha>(tree.refs[i], r, tmax, best)) {
          if constexpr (kAny) return true;
          found = true;
        }
      }
      return found;
    }
    for (uint32_t p = first; p < first + count; ++p) {
      alignas(16) float t[4], b1[4], b2[4];
      int mask = intersect_tri4(tree.packets[p], r.wr, r.tmin, tmax, t, b1, b2);
      if constexpr (kAlpha) {
        if (mask) mask = alpha_lanes(tree, tree.packets[p], mask, r, b1, b2, shape_override);
      }
      if (!mask) continue;
      if constexpr (kAny) return true;
      int lane = __builtin_ctz(unsigned(mask));
      for (mask &= mask - 1; mask; mask &= mask - 1) {
        const int l = __builtin_ctz(unsigned(mask));
        if (t[l] < t[lane]) lane = l;
      }
      const PrimRef pr = tree.refs[tree.packets[p].slot[lane]];
      tmax = t[lane];
      best = {t[lane], shape_override != kInvalidId ? shape_override : pr.shape, pr.prim, b1[lane], b2[lane]};
      found = true;
    }
    return found;
  }

  // The lanes of a triangle packet's hit mask whose hits the alpha test keeps.
  int alpha_lanes(const Tree& tree, const Tri4& packet, int mask, const TravRay& r, const float* b1, const float* b2,
                  uint32_t shape_override) const {
    for (int m = mask; m; m &= m - 1) {
      const int lane = __builtin_ctz(unsigned(m));
      const PrimRef pr = tree.refs[packet.slot[lane]];
      const uint32_t shape = shape_override != kInvalidId ? shape_override : pr.shape;
      if (g.shapes[shape].alpha && !alpha_keeps(g, *r.world, shape, ref_index(pr), {b1[lane], b2[lane]}, 0))
        mask &= ~(1 << lane);
    }
    return mask;
  }

  // A quadric, through its own object space. Kept out of line: inlined into other_prim, it pushes the sphere
  // and instance transforms there out of line too, which costs scenes without quadrics ~1% of their shadow queries.
  template <bool kAny>
  [[gnu::noinline]] bool quadric_prim(const PrimRef ref, Vec3f origin, const TravRay& r, float& tmax,
                                      Closest& best) const {
    Vec3f o = origin, d = r.d;
    to_object_space(quadric_to_object[ref_index(ref)], o, d);
    return object_space_quadric<kAny>(ref, o, d, r, tmax, best);
  }

  // The quadric of `ref` against the ray (o, d) in its object space.
  template <bool kAny>
  bool object_space_quadric(const PrimRef ref, Vec3f o, Vec3f d, const TravRay& r, float& tmax, Closest& best) const {
    const bool alpha = g.shapes[ref.shape].alpha;
    const auto h = intersect_quadric(g.quadrics[ref_index(ref)].quadric, o, d, r.tmin, tmax, [&](const QuadricHit& c) {
      return !alpha || alpha_keeps(g, *r.world, ref.shape, 0, c.uv, c.root);
    });
    if (!h) return false;
    tmax = h->t;
    if constexpr (!kAny) best = {h->t, ref.shape, 0, h->uv.x, h->uv.y};
    return true;
  }

  // A sphere, a quadric, an instance (whose prototype tree is traversed with the ray in object space) or a moving
  // mesh (its tree traversed with the ray moved back by the mesh's offset at the ray's time). An animated sphere,
  // quadric or instance takes the ray into its space at the ray's time.
  template <bool kAny, bool kAlpha>
  bool other_prim(const PrimRef ref, const TravRay& r, float& tmax, Closest& best) const {
    const Shape& shape = g.shapes[ref.shape];
    if (shape.animated >= 0) [[unlikely]]
      return animated_prim<kAny, kAlpha>(ref, r, tmax, best);
    const Vec3f origin = shape.translates() ? r.o - shape.offset_at(r.time) : r.o;
    if (ref_kind(ref) == kKindMovingMesh) {
      const TravRay back(Ray{origin, r.d, r.tmin, tmax, r.time}, r.world);
      return traverse<kAny, kAlpha>(moving_meshes[ref_index(ref)], back, tmax, best, ref.shape);
    }
    if (ref_kind(ref) == kKindSphere) {
      const uint32_t si = ref_index(ref);
      const SphereShape& s = g.spheres[si];
      Vec3f o = origin, d = r.d;
      if (sphere_transformed[si]) to_object_space(sphere_to_object[si], o, d);
      const auto t = intersect_sphere(o, d, s.center, s.radius, r.tmin, tmax);
      if (!t) return false;
      tmax = *t;
      if constexpr (!kAny) best = {*t, ref.shape, 0, 0.0f, 0.0f};
      return true;
    }
    if (ref_kind(ref) == kKindQuadric) return quadric_prim<kAny>(ref, origin, r, tmax, best);
    const uint32_t ii = ref_index(ref);
    Vec3f o = origin, d = r.d;
    to_object_space(instance_to_object[ii], o, d);
    const TravRay obj(Ray{o, d, r.tmin, tmax, r.time}, r.world);
    return traverse<kAny, kAlpha>(prototypes[g.instances[ii].prototype], obj, tmax, best, ref.shape);
  }

  template <bool kAny, bool kAlpha>
  bool animated_prim(const PrimRef ref, const TravRay& r, float& tmax, Closest& best) const {
    const Shape& shape = g.shapes[ref.shape];
    const Transform to_object = g.motions[size_t(shape.animated)].at(r.time).inverse();
    Vec3f o = r.o, d = r.d;
    to_object_space(to_object, o, d);
    if (ref_kind(ref) == kKindSphere) {
      const SphereShape& s = g.spheres[ref_index(ref)];
      const auto t = intersect_sphere(o, d, s.center, s.radius, r.tmin, tmax);
      if (!t) return false;
      tmax = *t;
      if constexpr (!kAny) best = {*t, ref.shape, 0, 0.0f, 0.0f};
      return true;
    }
    if (ref_kind(ref) == kKindQuadric) return object_space_quadric<kAny>(ref, o, d, r, tmax, best);
    const TravRay obj(Ray{o, d, r.tmin, tmax, r.time}, r.world);
    return traverse<kAny, kAlpha>(prototypes[g.instances[ref_index(ref)].prototype], obj, tmax, best, ref.shape);
  }
};

Bvh::Bvh(const WorldGeometry& geometry, const BvhOptions& options) : impl_(std::make_unique<Impl>(geometry, options)) {
  impl_->build();
}

Bvh::~Bvh() = default;

bool Bvh::intersect(const Ray& ray, Hit& hit) const {
  if (!traceable(ray)) return false;
  float tmax = ray.tmax;
  Closest best{ray.tmax};
  const TravRay r(ray, &ray);
  const bool found = impl_->g.alpha.opacity ? impl_->traverse<false, true>(impl_->world, r, tmax, best, kInvalidId)
                                            : impl_->traverse<false, false>(impl_->world, r, tmax, best, kInvalidId);
  if (!found) return false;
  const WorldGeometry& g = impl_->g;
  hit.t = best.t;
  hit.shape = best.shape;
  const Shape& s = g.shapes[best.shape];
  if (s.kind == ShapeKind::Sphere) {
    hit.prim = 0;
    hit.u = hit.v = 0.0f;
    Ray back = ray;  // a moving sphere is hit where it is at the ray's time
    if (s.translates()) back.o -= s.offset_at(ray.time);
    hit.ng = s.animated >= 0 ? sphere_world_normal(g.spheres[s.index], shape_to_world(g, s, ray.time), ray, best.t)
                             : sphere_world_normal(g.spheres[s.index], back, best.t);
  } else if (s.kind == ShapeKind::Quadric) {
    hit.prim = 0;
    hit.u = best.b1;
    hit.v = best.b2;
    Ray back = ray;
    if (s.translates()) back.o -= s.offset_at(ray.time);
    hit.ng = quadric_world_normal(quadric_at(g, s, ray.time), back, best.t);
  } else {
    hit.prim = best.prim;
    hit.u = best.b1;
    hit.v = best.b2;
    hit.ng = triangle_world_normal(g, best.shape, best.prim, ray.time);
  }
  return true;
}

bool Bvh::occluded(const Ray& ray) const {
  if (!traceable(ray)) return false;
  float tmax = ray.tmax;
  Closest unused{ray.tmax};
  const TravRay r(ray, &ray);
  return impl_->g.alpha.opacity ? impl_->traverse<true, true>(impl_->world, r, tmax, unused, kInvalidId)
                                : impl_->traverse<true, false>(impl_->world, r, tmax, unused, kInvalidId);
}

AccelStats Bvh::stats() const { return {"bvh", impl_->stats.build_seconds, impl_->stats.bytes}; }

const BvhStats& Bvh::bvh_stats() const { return impl_->stats; }

}  // namespace kiln
