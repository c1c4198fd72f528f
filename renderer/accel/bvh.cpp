#include "renderer/accel/bvh.h"

#include <chrono>

#include <tbb/parallel_for.h>

#include "renderer/accel/hit_point.h"
#include "renderer/accel/object_ray.h"
#include "renderer/accel/shape_bounds.h"
#include "renderer/accel/sphere_intersect.h"
#include "renderer/accel/triangle_intersect.h"

namespace kiln {
namespace {

// A leaf primitive: the shape it belongs to and, in the low bits of prim, the triangle / sphere / instance index;
// the top two bits say which.
struct PrimRef {
  uint32_t shape;
  uint32_t prim;
};
constexpr uint32_t kKindShift = 30;
constexpr uint32_t kIndexMask = (1u << kKindShift) - 1;
constexpr uint32_t kKindTriangle = 0, kKindSphere = 1, kKindInstance = 2;
inline uint32_t ref_kind(PrimRef r) { return r.prim >> kKindShift; }
inline uint32_t ref_index(PrimRef r) { return r.prim & kIndexMask; }

struct TriVerts {
  float v[9];  // v0, v1, v2
};

// Slab distances are rounded; enlarging the far distance by 2 gamma(3) makes the box test conservative so a
// triangle lying exactly on a box face is never culled (Ize 2013, "Robust BVH Ray Traversal").
constexpr float kSlabRobustScale = 1.0f + 2.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f);
// Direction components below this are clamped so 1/d stays finite and 0 * inf never produces NaN.
constexpr float kMinDirComponent = 1e-30f;
// Traversal stack entries; the builder caps the depth below this (kMaxDepth = 60 in bvh_build.cpp).
constexpr int kStackSize = 64;

struct Tree {
  std::vector<BvhNode, tbb::cache_aligned_allocator<BvhNode>> nodes;
  std::vector<PrimRef> refs;   // leaf order
  std::vector<TriVerts> tris;  // parallel to refs; unused for spheres and instances
  bool empty() const { return refs.empty(); }
  size_t bytes() const {
    return nodes.capacity() * sizeof(BvhNode) + refs.capacity() * sizeof(PrimRef) + tris.capacity() * sizeof(TriVerts);
  }
};

struct TravRay {
  Vec3f o, d, inv_d;
  WatertightRay wr;
  float tmin;
  explicit TravRay(const Ray& r) : o(r.o), d(r.d), wr(make_watertight_ray(r)), tmin(r.tmin) {
    for (int a = 0; a < 3; ++a) {
      const float c = std::abs(d[a]) >= kMinDirComponent ? d[a] : std::copysign(kMinDirComponent, d[a]);
      inv_d[a] = 1.0f / c;
    }
  }
};

inline bool box_hit(const BvhNode& n, const TravRay& r, float tmax, float& tnear) {
  const Vec3f t0 = (n.lo - r.o) * r.inv_d, t1 = (n.hi - r.o) * r.inv_d;
  const Vec3f tn = min(t0, t1), tf = max(t0, t1);
  tnear = std::max(r.tmin, max_component(tn));
  const float tfar = std::min(tmax, min_component(tf) * kSlabRobustScale);
  return tnear <= tfar;
}

struct Closest {
  float t;
  uint32_t shape = kInvalidId, prim = kInvalidId;
  float b1 = 0, b2 = 0;
};

}  // namespace

struct Bvh::Impl {
  const WorldGeometry& g;
  BvhOptions options;
  Tree world;
  std::vector<Tree> prototypes;             // empty trees for prototypes no instance uses
  std::vector<Transform> instance_to_object;
  std::vector<Transform> sphere_to_object;
  std::vector<uint8_t> sphere_transformed;
  BvhStats stats;

  Impl(const WorldGeometry& geometry, const BvhOptions& opt) : g(geometry), options(opt) {}

  // Triangle-only tree over one prototype mesh (object space).
  Tree build_mesh_tree(const TriangleMesh& m) const {
    const size_t n = m.triangle_count();
    std::vector<Bounds3f> bounds(n);
    tbb::parallel_for(size_t(0), n, [&](size_t t) {
      Bounds3f b(m.vertex(t, 0));
      b.extend(m.vertex(t, 1));
      b.extend(m.vertex(t, 2));
      bounds[t] = b;
    });
    std::vector<PrimRef> refs(n);
    for (size_t t = 0; t < n; ++t) refs[t] = {0, uint32_t(t)};
    return finish_tree(bounds, refs, [&](PrimRef) -> const TriangleMesh& { return m; });
  }

  // Builds over bounds, then stores refs and triangle vertices (of mesh_of(ref)) in leaf order.
  template <typename MeshOf>
  Tree finish_tree(const std::vector<Bounds3f>& bounds, const std::vector<PrimRef>& refs, MeshOf&& mesh_of) const {
    BvhBuildResult built = build_bvh(bounds, options.build);
    Tree t;
    t.nodes = std::move(built.nodes);
    const size_t n = built.order.size();
    t.refs.resize(n);
    t.tris.resize(n);
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
      const PrimRef r = refs[built.order[i]];
      t.refs[i] = r;
      if (ref_kind(r) != kKindTriangle) return;
      const TriangleMesh& m = mesh_of(r);
      for (int k = 0; k < 3; ++k) {
        const Vec3f v = m.vertex(ref_index(r), k);
        t.tris[i].v[3 * k] = v.x;
        t.tris[i].v[3 * k + 1] = v.y;
        t.tris[i].v[3 * k + 2] = v.z;
      }
    });
    return t;
  }

  void build() {
    const auto start = std::chrono::steady_clock::now();
    // Prototype trees first (instance bounds do not need them, but instance leaves do).
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

    // World primitives: triangles of world meshes (in shape order), then spheres, then instances.
    std::vector<size_t> first_tri(g.shapes.size() + 1, 0);
    for (size_t i = 0; i < g.shapes.size(); ++i) {
      const Shape& s = g.shapes[i];
      first_tri[i + 1] = first_tri[i] + (s.kind == ShapeKind::Mesh ? g.meshes[s.index].triangle_count() : 0);
    }
    const size_t ntri = first_tri.back();
    std::vector<Bounds3f> bounds(ntri);
    std::vector<PrimRef> refs(ntri);
    for (uint32_t i = 0; i < g.shapes.size(); ++i) {
      const Shape& s = g.shapes[i];
      if (s.kind != ShapeKind::Mesh) continue;
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
        bounds.push_back(sphere_world_bounds(g.spheres[s.index]));
        refs.push_back({i, (kKindSphere << kKindShift) | s.index});
      }
    }
    for (uint32_t i = 0; i < g.shapes.size(); ++i) {
      const Shape& s = g.shapes[i];
      if (s.kind == ShapeKind::Instance && !prototypes[g.instances[s.index].prototype].empty()) {
        bounds.push_back(instance_world_bounds(g, g.instances[s.index]));
        refs.push_back({i, (kKindInstance << kKindShift) | s.index});
      }
    }
    if (options.debug_drop_primitive && *options.debug_drop_primitive < refs.size()) {
      bounds.erase(bounds.begin() + ptrdiff_t(*options.debug_drop_primitive));
      refs.erase(refs.begin() + ptrdiff_t(*options.debug_drop_primitive));
    }
    world = finish_tree(bounds, refs, [&](PrimRef r) -> const TriangleMesh& { return g.meshes[g.shapes[r.shape].index]; });
    stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    stats.world = bvh_tree_stats(world.nodes, options.build);
    stats.bytes = world.bytes() + (instance_to_object.capacity() + sphere_to_object.capacity()) * sizeof(Transform);
    for (const Tree& t : prototypes) {
      if (t.empty()) continue;
      ++stats.prototype_trees;
      stats.prototype_nodes += t.nodes.size();
      stats.bytes += t.bytes();
    }
  }

  // Closest hit (kAny = false) or any hit (kAny = true) in tree with t in [ray.tmin, tmax]; tmax shrinks as
  // closer hits are found. shape_override names the instance shape when traversing a prototype tree.
  template <bool kAny>
  bool traverse(const Tree& tree, const TravRay& r, float& tmax, Closest& best, uint32_t shape_override) const {
    if (tree.empty()) return false;
    float tnear;
    if (!box_hit(tree.nodes[kBvhRoot], r, tmax, tnear)) return false;
    struct Entry {
      uint32_t node;
      float tnear;
    };
    Entry stack[kStackSize];
    int sp = 0;
    uint32_t node = kBvhRoot;
    bool found = false;
    const BvhNode* nodes = tree.nodes.data();
    for (;;) {
      const BvhNode& n = nodes[node];
      if (n.is_leaf()) {
        for (uint32_t i = n.offset, end = n.offset + n.count; i < end; ++i) {
          if (leaf_prim<kAny>(tree, i, r, tmax, best, shape_override)) {
            if constexpr (kAny) return true;
            found = true;
          }
        }
      } else {
        const uint32_t c = n.offset;
        float t0, t1;
        const bool h0 = box_hit(nodes[c], r, tmax, t0);
        const bool h1 = box_hit(nodes[c + 1], r, tmax, t1);
        if (h0 && h1) {
          const bool swap = t1 < t0;
          node = c + (swap ? 1 : 0);
          stack[sp++] = {c + (swap ? 0u : 1u), swap ? t0 : t1};
          continue;
        }
        if (h0 || h1) {
          node = h0 ? c : c + 1;
          continue;
        }
      }
      // Pop the next subtree still closer than the closest hit so far.
      for (;;) {
        if (sp == 0) return found;
        const Entry e = stack[--sp];
        if (e.tnear <= tmax) {
          node = e.node;
          break;
        }
      }
    }
  }

  template <bool kAny>
  bool leaf_prim(const Tree& tree, uint32_t i, const TravRay& r, float& tmax, Closest& best,
                 uint32_t shape_override) const {
    const PrimRef ref = tree.refs[i];
    const uint32_t kind = ref_kind(ref);
    if (kind == kKindTriangle) [[likely]] {
      const float* v = tree.tris[i].v;
      TriangleHit th;
      if (!intersect_triangle(r.wr, v, v + 3, v + 6, r.tmin, tmax, th)) return false;
      tmax = th.t;
      if constexpr (!kAny) best = {th.t, shape_override != kInvalidId ? shape_override : ref.shape, ref.prim, th.b1, th.b2};
      return true;
    }
    if (kind == kKindSphere) {
      const uint32_t si = ref_index(ref);
      const SphereShape& s = g.spheres[si];
      Vec3f o = r.o, d = r.d;
      if (sphere_transformed[si]) to_object_space(sphere_to_object[si], o, d);
      const auto t = intersect_sphere(o, d, s.center, s.radius, r.tmin, tmax);
      if (!t) return false;
      tmax = *t;
      if constexpr (!kAny) best = {*t, ref.shape, 0, 0.0f, 0.0f};
      return true;
    }
    const uint32_t ii = ref_index(ref);
    Vec3f o = r.o, d = r.d;
    to_object_space(instance_to_object[ii], o, d);
    const TravRay obj(Ray{o, d, r.tmin, tmax});
    return traverse<kAny>(prototypes[g.instances[ii].prototype], obj, tmax, best, ref.shape);
  }
};

Bvh::Bvh(const WorldGeometry& geometry, const BvhOptions& options)
    : impl_(std::make_unique<Impl>(geometry, options)) {
  impl_->build();
}

Bvh::~Bvh() = default;

bool Bvh::intersect(const Ray& ray, Hit& hit) const {
  float tmax = ray.tmax;
  Closest best{ray.tmax};
  if (!impl_->traverse<false>(impl_->world, TravRay(ray), tmax, best, kInvalidId)) return false;
  const WorldGeometry& g = impl_->g;
  hit.t = best.t;
  hit.shape = best.shape;
  const Shape& s = g.shapes[best.shape];
  if (s.kind == ShapeKind::Sphere) {
    hit.prim = 0;
    hit.u = hit.v = 0.0f;
    hit.ng = sphere_world_normal(g.spheres[s.index], ray, best.t);
  } else {
    hit.prim = best.prim;
    hit.u = best.b1;
    hit.v = best.b2;
    hit.ng = triangle_world_normal(g, best.shape, best.prim);
  }
  return true;
}

bool Bvh::occluded(const Ray& ray) const {
  float tmax = ray.tmax;
  Closest unused{ray.tmax};
  return impl_->traverse<true>(impl_->world, TravRay(ray), tmax, unused, kInvalidId);
}

AccelStats Bvh::stats() const { return {"bvh", impl_->stats.build_seconds, impl_->stats.bytes}; }

const BvhStats& Bvh::bvh_stats() const { return impl_->stats; }

}  // namespace kiln
