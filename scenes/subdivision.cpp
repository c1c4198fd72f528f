// Loop subdivision (Loop 1987 with Warren's beta, the rules of pbrt's loopsubdiv):
//  - every triangle splits into four around one new vertex per edge: V' = V + E, T' = 4 T, winding kept; old
//    vertices keep their indices, so a mesh subdivided n levels starts with the vertices of every coarser level;
//  - interior edge (two faces): 3/8 (a + b) + 1/8 (c + d), c and d the vertices opposite the edge;
//  - interior vertex of valence n: (1 - n beta) v + beta * sum(ring), beta = 3/16 for n = 3, else 3/(8n);
//  - crease edges, i.e. boundary edges (one face) and non-manifold edges (more than two faces): the midpoint;
//    a vertex on exactly two crease edges follows the curve rule 1/8, 6/8, 1/8 along them; a vertex on one or on
//    more than two crease edges is a corner and stays put.
// The last level also yields every vertex's exact limit-surface normal from Loop's tangent masks (interior: the
// ring's first Fourier modes; boundary: the along-curve tangent and the exact across eigenvector of these rules,
// see across_mask), oriented like the adjacent faces. Where the one-ring is not a single fan (non-manifold,
// inconsistent winding, degenerate triangles) the area-weighted face normal is used instead. Positions are the
// last level's control points (not projected onto the limit surface). Per-vertex uvs are carried linearly (edge
// vertices take the edge midpoint's uv); input normals are replaced by the limit normals and smooth is set.
//
// Speed and memory: flat arrays only, no per-vertex allocation. Per level, one counting sort of the half-edges by
// endpoint (each half-edge listed under both endpoints as (other endpoint << 32 | half-edge), sorted per vertex)
// gives every vertex its edges with their face counts; vertex points, edge points, new triangles and (last level)
// normals are then TBB loops over vertices or triangles. The limit normal does not depend on the level, so the
// last level's normals come from the coarse level's adjacency (old vertices: coarse ring; new edge vertices: their
// fine ring, known from the two coarse triangles), and the fine mesh needs no adjacency of its own. Results do
// not depend on the thread count (per-vertex lists are sorted).
#include "scenes/subdivision.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"

namespace kiln {
namespace {

// Loop's weights.
constexpr float kEdgeAdjacentWeight = 3.0f / 8.0f;   // the edge's endpoints
constexpr float kEdgeOppositeWeight = 1.0f / 8.0f;   // the vertices opposite the edge
constexpr float kCreaseNeighbourWeight = 1.0f / 8.0f;
constexpr float kCreaseSelfWeight = 6.0f / 8.0f;
constexpr float kValence3Beta = 3.0f / 16.0f;

// Rings longer than this fall back to the face-averaged normal (stack arrays in the normal pass).
constexpr size_t kMaxRingForLimitNormal = 64;
// TBB grain sizes: enough work per task to amortise scheduling.
constexpr size_t kVertexGrain = 2048;
constexpr size_t kHalfEdgeGrain = 8192;

inline float loop_beta(uint32_t valence) {
  return valence == 3 ? kValence3Beta : 3.0f / (8.0f * float(valence));
}

// Corner h of triangle h / 3 starts the half-edge idx[h] -> idx[next(h)]; idx[prev(h)] is opposite it.
inline uint32_t next_corner(uint32_t h) { return h % 3 == 2 ? h - 2 : h + 1; }
inline uint32_t prev_corner(uint32_t h) { return h % 3 == 0 ? h + 2 : h - 1; }

struct MeshView {
  std::span<const Vec3f> p;
  std::span<const uint32_t> idx;
  std::span<const Vec2f> uv;  // empty, or one per vertex
};

struct Level {
  std::vector<Vec3f> p;
  std::vector<uint32_t> idx;
  std::vector<Vec2f> uv;
  std::vector<Vec3f> n;  // limit normals, last level only
  MeshView view() const { return {p, idx, uv}; }
};

template <typename F>
void parallel_range(size_t n, size_t grain, F&& body) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                    [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
}

inline void atomic_increment(uint32_t& counter) {
  std::atomic_ref<uint32_t>(counter).fetch_add(1, std::memory_order_relaxed);
}
inline uint32_t atomic_claim(uint32_t& cursor) {
  return std::atomic_ref<uint32_t>(cursor).fetch_add(1, std::memory_order_relaxed);
}

// Exclusive prefix sum in place; returns the total. counts has n + 1 entries, the last receives the total.
uint32_t exclusive_scan(std::vector<uint32_t>& counts) {
  uint32_t sum = 0;
  for (uint32_t& c : counts) {
    const uint32_t k = c;
    c = sum;
    sum += k;
  }
  return sum;
}

// A compressed per-vertex list: entries of vertex v are entry[offset[v] .. offset[v + 1]).
template <typename T>
struct VertexLists {
  std::vector<uint32_t> offset;
  std::vector<T> entry;
  std::span<const T> of(size_t v) const { return {entry.data() + offset[v], entry.data() + offset[v + 1]}; }
};

// Per vertex, every half-edge touching it as (other endpoint << 32 | half-edge), sorted: equal other endpoints
// are adjacent, so each run is one edge and its length is the edge's face count. A degenerate half-edge (both
// endpoints equal) is listed once.
VertexLists<uint64_t> edge_star(size_t nv, std::span<const uint32_t> idx) {
  const size_t nh = idx.size();
  VertexLists<uint64_t> s;
  s.offset.assign(nv + 1, 0);
  parallel_range(nh, kHalfEdgeGrain, [&](size_t b, size_t e) {
    for (size_t h = b; h < e; ++h) {
      const uint32_t v0 = idx[h], v1 = idx[next_corner(uint32_t(h))];
      atomic_increment(s.offset[v0]);
      if (v1 != v0) atomic_increment(s.offset[v1]);
    }
  });
  s.entry.resize(exclusive_scan(s.offset));
  std::vector<uint32_t> cursor(s.offset.begin(), s.offset.end() - 1);
  parallel_range(nh, kHalfEdgeGrain, [&](size_t b, size_t e) {
    for (size_t h = b; h < e; ++h) {
      const uint32_t v0 = idx[h], v1 = idx[next_corner(uint32_t(h))];
      s.entry[atomic_claim(cursor[v0])] = (uint64_t(v1) << 32) | h;
      if (v1 != v0) s.entry[atomic_claim(cursor[v1])] = (uint64_t(v0) << 32) | h;
    }
  });
  parallel_range(nv, kVertexGrain, [&](size_t b, size_t e) {
    for (size_t v = b; v < e; ++v) std::sort(s.entry.begin() + s.offset[v], s.entry.begin() + s.offset[v + 1]);
  });
  return s;
}

inline uint32_t other_of(uint64_t entry) { return uint32_t(entry >> 32); }
inline uint32_t half_edge_of(uint64_t entry) { return uint32_t(entry); }

// Calls f(other, run) for each edge of vertex v; run holds the edge's half-edges (one per adjacent face).
template <typename F>
void for_each_edge(std::span<const uint64_t> star, F&& f) {
  for (size_t i = 0; i < star.size();) {
    const uint32_t other = other_of(star[i]);
    size_t j = i + 1;
    while (j < star.size() && other_of(star[j]) == other) ++j;
    f(other, star.subspan(i, j - i));
    i = j;
  }
}

// Across-boundary tangent masks. For a boundary vertex v with fan p_0..p_k (k faces), one level maps
// (v, p_0..p_k) to (v', p_0'..p_k') by the rules above; the limit tangent across the boundary is the dominant left
// eigenvector of that local matrix among masks that sum to zero (no eigenvalue-1 limit-position part) and are
// symmetric under reversing the fan (no along-the-boundary part). Found once per k by power iteration, started
// from Hoppe et al.'s mask (pbrt's), which is exact for k <= 3; for k >= 4 the exact eigenvalue exceeds 1/2 and
// Hoppe's mask is not an eigenvector of these rules.
using Mask = std::vector<double>;  // weights for v, p_0 .. p_k

Mask apply_boundary_step(const Mask& x, size_t k) {
  Mask y(k + 2, 0.0);
  auto add = [&](size_t row, size_t col, double w) { y[col] += x[row] * w; };
  add(0, 0, kCreaseSelfWeight);
  add(0, 1, kCreaseNeighbourWeight);
  add(0, k + 1, kCreaseNeighbourWeight);
  for (size_t i = 0; i <= k; ++i) {
    const size_t r = 1 + i;
    if (i == 0 || i == k) {  // boundary edge: midpoint
      add(r, 0, 0.5);
      add(r, r, 0.5);
    } else {
      add(r, 0, kEdgeAdjacentWeight);
      add(r, r, kEdgeAdjacentWeight);
      add(r, r - 1, kEdgeOppositeWeight);
      add(r, r + 1, kEdgeOppositeWeight);
    }
  }
  return y;
}

Mask across_mask(size_t k) {
  constexpr double kPiD = 3.14159265358979323846;
  constexpr double kBoundaryLimitSelf = 2.0 / 3.0, kBoundaryLimitNeighbour = 1.0 / 6.0;  // the limit position
  constexpr double kTolerance = 1e-14;
  constexpr int kMaxIterations = 2000;
  const size_t m = k + 1;  // ring length
  Mask x(k + 2, 0.0);
  if (m == 2) {
    x = {-2, 1, 1};
  } else if (m == 3) {
    x = {-1, 0, 1, 0};
  } else if (m == 4) {
    x = {-2, -1, 2, 2, -1};
  } else {
    const double theta = kPiD / double(m - 1);
    x[1] = x[m] = std::sin(theta);
    for (size_t j = 1; j + 1 < m; ++j) x[1 + j] = (2.0 * std::cos(theta) - 2.0) * std::sin(double(j) * theta);
  }
  for (int it = 0; it < kMaxIterations; ++it) {
    Mask y = apply_boundary_step(x, k);
    double sum = 0;
    for (double w : y) sum += w;
    y[0] -= sum * kBoundaryLimitSelf;  // remove the limit-position component rounding lets in
    y[1] -= sum * kBoundaryLimitNeighbour;
    y[k + 1] -= sum * kBoundaryLimitNeighbour;
    for (size_t i = 0; i <= k / 2; ++i) y[1 + i] = y[1 + k - i] = 0.5 * (y[1 + i] + y[1 + k - i]);
    double scale = 0;
    for (double w : y) scale = std::max(scale, std::abs(w));
    double change = 0;
    for (size_t i = 0; i < y.size(); ++i) {
      y[i] /= scale;
      change = std::max(change, std::abs(y[i] - x[i]));
    }
    x = std::move(y);
    if (change < kTolerance) break;
  }
  return x;
}

const Mask& across_mask_cached(size_t k) {
  static const std::vector<Mask> table = [] {
    std::vector<Mask> t(kMaxRingForLimitNormal);
    for (size_t kk = 1; kk < kMaxRingForLimitNormal; ++kk) t[kk] = across_mask(kk);
    return t;
  }();
  return table[k];
}

// (cos, sin)(2 pi i / n), i < n, for rings of n <= kMaxRingForLimitNormal vertices.
const std::vector<Vec2f>& fourier_weights(size_t n) {
  static const std::vector<std::vector<Vec2f>> table = [] {
    std::vector<std::vector<Vec2f>> t(kMaxRingForLimitNormal + 1);
    for (size_t m = 1; m <= kMaxRingForLimitNormal; ++m)
      for (size_t i = 0; i < m; ++i) {
        const double phi = 2.0 * 3.14159265358979323846 * double(i) / double(m);
        t[m].push_back(Vec2f(float(std::cos(phi)), float(std::sin(phi))));
      }
    return t;
  }();
  return table[n];
}

// Limit-surface tangents from the ordered ring; the normal is their cross product (orientation fixed by the
// caller).
Vec3f limit_normal(Vec3f pv, const Vec3f* ring, size_t n, bool closed) {
  if (closed) {  // Loop's interior masks: the ring's first Fourier modes (exact eigenvectors for any beta)
    const std::vector<Vec2f>& w = fourier_weights(n);
    Vec3f t1(0.0f), t2(0.0f);
    for (size_t i = 0; i < n; ++i) {
      t1 += w[i].x * ring[i];
      t2 += w[i].y * ring[i];
    }
    return cross(t1, t2);
  }
  const Vec3f along = ring[n - 1] - ring[0];  // the boundary curve's tangent (cubic B-spline)
  const Mask& mask = across_mask_cached(n - 1);
  Vec3f across = float(mask[0]) * pv;
  for (size_t i = 0; i < n; ++i) across += float(mask[1 + i]) * ring[i];
  return cross(along, across);
}

// Orders the one-ring of v from its triangles (v, a[i], b[i]) (counter-clockwise seen from the front): returns
// the ring length, and whether it is a closed loop (interior vertex) or an open fan (boundary vertex, ring runs
// from one boundary neighbour to the other). 0 when the triangles do not form one consistent fan.
size_t order_ring(uint32_t v, std::span<const uint32_t> a, std::span<const uint32_t> b, uint32_t* ring,
                  bool& closed) {
  const size_t n = a.size();
  std::array<bool, kMaxRingForLimitNormal> used{};
  size_t start = n;  // the boundary fan starts at the triangle whose a is nobody's b
  for (size_t i = 0; i < n; ++i) {
    if (a[i] == v || b[i] == v || a[i] == b[i]) return 0;
    if (std::find(b.begin(), b.end(), a[i]) == b.end()) {
      if (start != n) return 0;  // two fans meet at v
      start = i;
    }
  }
  closed = start == n;
  if (closed) start = 0;
  ring[0] = a[start];
  size_t cur = start, len = 1;
  for (size_t step = 0; step < n; ++step) {
    used[cur] = true;
    ring[len++] = b[cur];
    if (step + 1 == n) break;
    size_t nxt = n;
    for (size_t j = 0; j < n; ++j)
      if (!used[j] && a[j] == b[cur]) {
        if (nxt != n) return 0;  // ambiguous continuation
        nxt = j;
      }
    if (nxt == n) return 0;
    cur = nxt;
  }
  if (closed) {
    if (ring[len - 1] != ring[0]) return 0;
    --len;  // the loop's last entry repeats its first
  } else if (ring[len - 1] == ring[0]) {
    return 0;
  }
  return len;
}

// Positions (and uvs) of one level; edge_vertex names the new vertex on each half-edge's edge.
Level refine_positions(const MeshView& in, const VertexLists<uint64_t>& star, std::vector<uint32_t>& edge_vertex) {
  const size_t nv = in.p.size(), nh = in.idx.size();
  const bool has_uv = !in.uv.empty();

  // Each edge belongs to its smaller endpoint (a degenerate edge to its only one); number them per vertex.
  std::vector<uint32_t> edge_base(nv + 1, 0);
  parallel_range(nv, kVertexGrain, [&](size_t b, size_t e) {
    for (size_t v = b; v < e; ++v)
      for_each_edge(star.of(v), [&](uint32_t other, std::span<const uint64_t>) { edge_base[v] += other >= v; });
  });
  const size_t ne = exclusive_scan(edge_base);

  Level out;
  out.p.resize(nv + ne);
  if (has_uv) out.uv.resize(nv + ne);
  edge_vertex.resize(nh);
  parallel_range(nv, kVertexGrain, [&](size_t b, size_t e) {
    for (size_t vi = b; vi < e; ++vi) {
      const uint32_t v = uint32_t(vi);
      const Vec3f pv = in.p[v];
      Vec3f ring(0.0f), crease(0.0f);
      uint32_t valence = 0, creases = 0;
      uint32_t next_edge = uint32_t(nv) + edge_base[v];
      for_each_edge(star.of(v), [&](uint32_t other, std::span<const uint64_t> run) {
        const bool smooth_edge = run.size() == 2 && other != v;
        if (other != v) {
          ring += in.p[other];
          ++valence;
          if (!smooth_edge) {
            crease += in.p[other];
            ++creases;
          }
        }
        if (other < v) return;
        const uint32_t ev = next_edge++;
        if (smooth_edge) {
          const uint32_t c = in.idx[prev_corner(half_edge_of(run[0]))], d = in.idx[prev_corner(half_edge_of(run[1]))];
          out.p[ev] = kEdgeAdjacentWeight * (pv + in.p[other]) + kEdgeOppositeWeight * (in.p[c] + in.p[d]);
        } else {
          out.p[ev] = 0.5f * (pv + in.p[other]);
        }
        if (has_uv) out.uv[ev] = (in.uv[v] + in.uv[other]) * 0.5f;
        for (uint64_t entry : run) edge_vertex[half_edge_of(entry)] = ev;
      });
      if (has_uv) out.uv[v] = in.uv[v];
      if (creases == 0 && valence > 0) {
        const float beta = loop_beta(valence);
        out.p[v] = (1.0f - float(valence) * beta) * pv + beta * ring;
      } else if (creases == 2) {
        out.p[v] = kCreaseSelfWeight * pv + kCreaseNeighbourWeight * crease;
      } else {
        out.p[v] = pv;  // corner (or isolated vertex)
      }
    }
  });

  out.idx.resize(4 * nh);
  parallel_range(nh / 3, kHalfEdgeGrain, [&](size_t b, size_t e) {
    for (size_t t = b; t < e; ++t) {
      const uint32_t v0 = in.idx[3 * t], v1 = in.idx[3 * t + 1], v2 = in.idx[3 * t + 2];
      const uint32_t e0 = edge_vertex[3 * t], e1 = edge_vertex[3 * t + 1], e2 = edge_vertex[3 * t + 2];
      const std::array<uint32_t, 12> tris{v0, e0, e2, e0, v1, e1, e2, e1, v2, e0, e1, e2};
      std::copy(tris.begin(), tris.end(), out.idx.begin() + ptrdiff_t(12 * t));
    }
  });
  return out;
}

// Per triangle, twice its area times its unit normal.
std::vector<Vec3f> face_normals(const MeshView& m) {
  std::vector<Vec3f> n(m.idx.size() / 3);
  parallel_range(n.size(), kHalfEdgeGrain, [&](size_t b, size_t e) {
    for (size_t t = b; t < e; ++t) {
      const Vec3f p0 = m.p[m.idx[3 * t]];
      n[t] = cross(m.p[m.idx[3 * t + 1]] - p0, m.p[m.idx[3 * t + 2]] - p0);
    }
  });
  return n;
}

inline Vec3f unit_or_zero(Vec3f n) {
  const float len2 = length_squared(n);
  return len2 > 0.0f && std::isfinite(len2) ? n / std::sqrt(len2) : Vec3f(0.0f);
}

// The limit normal n, turned to the side of `reference` (the adjacent faces' normal); reference itself where n
// is unusable.
inline Vec3f oriented(Vec3f n, Vec3f reference) {
  if (!is_finite(n) || length_squared(n) == 0.0f) return unit_or_zero(reference);
  return unit_or_zero(dot(n, reference) < 0.0f ? -n : n);
}

// Limit normals of the refined mesh `out`, computed while the coarse level's adjacency is at hand. The limit
// normal is level-independent, so an old vertex takes it from its coarse one-ring. A new vertex on an interior
// edge (a, b) with opposite vertices c, d is regular (valence 6) with fine ring a', e_ca, e_bc, b', e_db, e_ad; on
// a boundary edge its fine fan is a', e_ca, e_bc, b' (3 faces).
std::vector<Vec3f> limit_normals(const MeshView& in, const VertexLists<uint64_t>& star,
                                 const std::vector<uint32_t>& edge_vertex, const Level& out) {
  std::vector<Vec3f> normals(out.p.size(), Vec3f(0.0f));
  const std::vector<Vec3f> face_n = face_normals(in);
  parallel_range(in.p.size(), kVertexGrain, [&](size_t b, size_t e) {
    std::array<uint32_t, kMaxRingForLimitNormal> fan_a, fan_b, ring;
    std::array<Vec3f, kMaxRingForLimitNormal> ring_p;
    for (size_t vi = b; vi < e; ++vi) {
      const uint32_t v = uint32_t(vi);
      const std::span<const uint64_t> entries = star.of(v);
      // Old vertex: its triangles (v, a, b) from the half-edges leaving it.
      Vec3f face_sum(0.0f);
      size_t fans = 0;
      bool fan_fits = true;
      for (uint64_t entry : entries) {
        const uint32_t h = half_edge_of(entry);
        if (in.idx[h] != v) continue;
        face_sum += face_n[h / 3];
        if (fans == kMaxRingForLimitNormal - 1) {
          fan_fits = false;
          continue;
        }
        fan_a[fans] = in.idx[next_corner(h)];
        fan_b[fans] = in.idx[prev_corner(h)];
        ++fans;
      }
      Vec3f n(0.0f);
      if (fan_fits && fans > 0) {
        bool closed = false;
        const size_t len = order_ring(v, {fan_a.data(), fans}, {fan_b.data(), fans}, ring.data(), closed);
        if (len >= (closed ? 3u : 2u)) {
          for (size_t i = 0; i < len; ++i) ring_p[i] = in.p[ring[i]];
          n = limit_normal(in.p[v], ring_p.data(), len, closed);
        }
      }
      normals[v] = oriented(n, face_sum);

      // New vertices on the edges v owns.
      for_each_edge(entries, [&](uint32_t other, std::span<const uint64_t> run) {
        if (other < v) return;
        const uint32_t ev = edge_vertex[half_edge_of(run[0])];
        Vec3f faces(0.0f);
        for (uint64_t entry : run) faces += face_n[half_edge_of(entry) / 3];
        Vec3f en(0.0f);
        const uint32_t h1 = half_edge_of(run[0]);
        if (other != v && run.size() == 2 && in.idx[half_edge_of(run[1])] != in.idx[h1]) {
          const uint32_t h2 = half_edge_of(run[1]);  // the twin, opposite direction
          const Vec3f r[6] = {out.p[in.idx[h1]],          out.p[edge_vertex[prev_corner(h1)]],
                              out.p[edge_vertex[next_corner(h1)]], out.p[in.idx[h2]],
                              out.p[edge_vertex[prev_corner(h2)]], out.p[edge_vertex[next_corner(h2)]]};
          en = limit_normal(out.p[ev], r, 6, true);
        } else if (other != v && run.size() == 1) {
          const Vec3f r[4] = {out.p[in.idx[h1]], out.p[edge_vertex[prev_corner(h1)]],
                              out.p[edge_vertex[next_corner(h1)]], out.p[in.idx[next_corner(h1)]]};
          en = limit_normal(out.p[ev], r, 4, false);
        }
        normals[ev] = oriented(en, faces);
      });
    }
  });
  return normals;
}

Level refine(const MeshView& in, bool with_normals) {
  const VertexLists<uint64_t> star = edge_star(in.p.size(), in.idx);
  std::vector<uint32_t> edge_vertex;
  Level out = refine_positions(in, star, edge_vertex);
  if (with_normals) out.n = limit_normals(in, star, edge_vertex, out);
  return out;
}

void check_input(const MeshDesc& mesh, int levels) {
  if (mesh.indices.size() % 3 != 0)
    throw Error(mesh.name, "", "Loop subdivision: index count " + std::to_string(mesh.indices.size()) +
                                   " is not a multiple of 3");
  const size_t nv = mesh.positions.size();
  for (uint32_t i : mesh.indices)
    if (i >= nv)
      throw Error(mesh.name, "", "Loop subdivision: vertex index " + std::to_string(i) + " is out of range (" +
                                     std::to_string(nv) + " vertices)");
  // Half-edge ids and per-vertex list offsets are 32-bit: the last level's 3 * T' (and 2 * 3T) must fit.
  constexpr double kMaxHalfEdges = double(std::numeric_limits<uint32_t>::max());
  const double half_edges = double(mesh.indices.size()) * std::pow(4.0, levels);
  if (half_edges > kMaxHalfEdges)
    throw Error(mesh.name, "", "Loop subdivision: " + std::to_string(levels) + " levels would make " +
                                   std::to_string(uint64_t(half_edges / 3)) +
                                   " triangles, more than Kiln's 32-bit mesh indices allow");
}

}  // namespace

MeshDesc loop_subdivide(const MeshDesc& mesh, int levels) {
  if (levels <= 0) return mesh;
  check_input(mesh, levels);
  const bool uv = mesh.uvs.size() == mesh.positions.size() && !mesh.uvs.empty();
  const MeshView base{mesh.positions, mesh.indices, uv ? std::span<const Vec2f>(mesh.uvs) : std::span<const Vec2f>{}};
  Level cur = refine(base, levels == 1);
  for (int l = 1; l < levels; ++l) cur = refine(cur.view(), l + 1 == levels);

  // Every field but the geometry is carried over.
  MeshDesc out;
  out.name = mesh.name;
  out.material = mesh.material;
  out.to_world = mesh.to_world;
  out.emission = mesh.emission;
  out.is_instance_base = mesh.is_instance_base;
  out.visible = mesh.visible;
  out.subdivide = 0;
  out.smooth = true;
  if (!cur.idx.empty()) out.normals = std::move(cur.n);
  out.positions = std::move(cur.p);
  out.indices = std::move(cur.idx);
  out.uvs = std::move(cur.uv);
  return out;
}

void apply_subdivision(SceneDesc& scene) {
  for (MeshDesc& m : scene.meshes)
    if (m.subdivide > 0) {
      m = loop_subdivide(m, m.subdivide);
      m.subdivide = 0;
    }
}

}  // namespace kiln
