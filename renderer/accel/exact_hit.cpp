#include "renderer/accel/exact_hit.h"

#include <algorithm>
#include <cmath>

namespace kiln {
namespace {

constexpr double kFloatEpsilon = 0x1p-24;

struct D3 {
  double x, y, z;
};
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 to_d(Vec3f v) { return {v.x, v.y, v.z}; }

// Affine map of a float matrix applied in double (w = 1 for points, 0 for vectors).
D3 apply(const Mat4& m, D3 p, double w) {
  const auto& a = m.m;
  return {a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3] * w,
          a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3] * w,
          a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3] * w};
}

ExactHit exact_triangle(const Ray& ray, D3 v0, D3 v1, D3 v2) {
  // Moller-Trumbore in double.
  ExactHit r;
  const D3 o = to_d(ray.o), d = to_d(ray.d);
  const D3 e1 = v1 - v0, e2 = v2 - v0;
  const D3 p = cross(d, e2);
  const double det = dot(e1, p);
  if (det == 0.0) return r;
  const D3 s = o - v0;
  const double b1 = dot(s, p) / det;
  const D3 q = cross(s, e1);
  const double b2 = dot(d, q) / det;
  const double b0 = 1.0 - b1 - b2;
  r.t = dot(e2, q) / det;
  r.where = Vec2f(float(b1), float(b2));
  r.in_range = r.t >= ray.tmin && r.t <= ray.tmax;
  r.hit = std::min({b0, b1, b2}) >= 0.0 && r.in_range;
  // World distance of the crossing from each edge: barycentric times the triangle's height over that edge.
  const double area2 = std::sqrt(dot(cross(e1, e2), cross(e1, e2)));
  const D3 e12 = v2 - v1;
  const double dist[3] = {b0 * area2 / std::sqrt(dot(e12, e12)), b1 * area2 / std::sqrt(dot(e2, e2)),
                          b2 * area2 / std::sqrt(dot(e1, e1))};
  const double reach =
      std::max({std::sqrt(dot(v0 - o, v0 - o)), std::sqrt(dot(v1 - o, v1 - o)), std::sqrt(dot(v2 - o, v2 - o))});
  const double noise = kEdgeNoiseUlps * kFloatEpsilon * reach;
  r.near_edge = std::min({std::abs(dist[0]), std::abs(dist[1]), std::abs(dist[2])}) <= noise;
  return r;
}

// offset: where the (moving) sphere is at the ray's time relative to time 0; to_world its transform then.
ExactHit exact_sphere(const Ray& ray, const SphereShape& s, const Transform& to_world, D3 offset) {
  ExactHit r;
  const Mat4& inv = to_world.inverse_matrix();
  const D3 o = apply(inv, to_d(ray.o) - offset, 1.0), d = apply(inv, to_d(ray.d), 0.0);
  const D3 f = o - to_d(s.center);
  const double a = dot(d, d), b = -dot(f, d), rr = double(s.radius) * s.radius;
  const D3 l = {f.x + d.x * (b / a), f.y + d.y * (b / a), f.z + d.z * (b / a)};
  const double gap = rr - dot(l, l);  // > 0: the line passes inside the silhouette
  // gap = (r - |l|)(r + |l|): the line's distance from the silhouette times ~2r.
  const double noise = kEdgeNoiseUlps * kFloatEpsilon * (std::sqrt(dot(f, f)) + s.radius);
  r.near_edge = std::abs(gap) <= noise * 2.0 * s.radius;
  // Beside the silhouette, the closest approach stands in for the crossing.
  const double q = b + std::copysign(std::sqrt(a * std::max(gap, 0.0)), b);
  double t0 = q != 0.0 ? (dot(f, f) - rr) / q : b / a, t1 = q != 0.0 ? q / a : b / a;
  if (t0 > t1) std::swap(t0, t1);
  r.t = t0 >= ray.tmin ? t0 : t1;
  r.in_range = r.t >= ray.tmin && r.t <= ray.tmax;
  r.hit = gap >= 0.0 && r.in_range;
  return r;
}

double length(D3 a) { return std::sqrt(dot(a, a)); }

// Signed world-unit distance of a point of the quadric's unbounded surface from the limits of its shape (z range or
// disk radii, phi_max): positive inside.
double quadric_margin(const Quadric& q, D3 p) {
  const double ring = std::sqrt(p.x * p.x + p.y * p.y);
  double margin = q.type == QuadricType::Disk ? std::min(double(q.radius) - ring, ring - double(q.inner_radius))
                                              : std::min(p.z - double(q.z_min), double(q.z_max) - p.z);
  if (!q.full_turn()) {
    double phi = std::atan2(p.y, p.x);
    if (phi < 0.0) phi += 2.0 * 3.14159265358979323846;
    const double phi_max = q.phi_max;
    margin = std::min(margin, ring * (phi <= phi_max ? std::min(phi, phi_max - phi)
                                                     : -std::min(phi - phi_max, 2.0 * 3.14159265358979323846 - phi)));
  }
  return margin;
}

// offset: as for exact_sphere.
ExactHit exact_quadric(const Ray& ray, const QuadricShape& shape, D3 offset) {
  ExactHit r;
  const Quadric& q = shape.quadric;
  const Mat4& inv = shape.to_world.inverse_matrix();
  const D3 o = apply(inv, to_d(ray.o) - offset, 1.0), d = apply(inv, to_d(ray.d), 0.0);
  const double noise = kEdgeNoiseUlps * kFloatEpsilon *
                       (length(o) + q.radius + std::max({std::abs(q.z_min), std::abs(q.z_max), std::abs(q.height)}));
  double roots[2];
  int n = 0;
  bool silhouette = false, beside = false;  // near the silhouette; the line misses it (in exact arithmetic)
  if (q.type == QuadricType::Disk) {
    if (d.z == 0.0) return r;
    roots[n++] = (double(q.height) - o.z) / d.z;
  } else {
    const bool sphere = q.type == QuadricType::Sphere;
    const D3 f = sphere ? o : D3{o.x, o.y, 0.0}, dd = sphere ? d : D3{d.x, d.y, 0.0};
    const double a = dot(dd, dd), b = -dot(f, dd), rr = double(q.radius) * q.radius;
    if (a == 0.0) return r;
    const D3 l = {f.x + dd.x * (b / a), f.y + dd.y * (b / a), f.z + dd.z * (b / a)};
    const double gap = rr - dot(l, l);  // > 0: the line passes inside the silhouette
    silhouette = std::abs(gap) <= noise * 2.0 * q.radius;
    if (gap < 0.0 && !silhouette) return r;
    // Beside the silhouette, the closest approach stands in for both crossings.
    const double qq = b + std::copysign(std::sqrt(a * std::max(gap, 0.0)), b);
    double t0 = qq != 0.0 ? (dot(f, f) - rr) / qq : b / a, t1 = qq != 0.0 ? qq / a : b / a;
    if (t0 > t1) std::swap(t0, t1);
    roots[n++] = t0;
    roots[n++] = t1;
    beside = gap < 0.0;
  }
  for (int i = 0; i < n; ++i) {
    const double t = roots[i];
    if (!(t >= ray.tmin && t <= ray.tmax)) continue;
    const D3 p = {o.x + d.x * t, o.y + d.y * t, o.z + d.z * t};
    const double margin = quadric_margin(q, p);
    const bool near = std::abs(margin) <= noise;
    if (margin < 0.0 && !near) continue;
    r.t = t;
    r.in_range = true;
    r.near_edge = near || silhouette;
    r.hit = margin >= 0.0 && !beside;
    r.where = q.uv(q.project(Vec3f(float(p.x), float(p.y), float(p.z))));
    r.root = uint32_t(i);
    return r;
  }
  return r;
}

}  // namespace

ExactHit exact_hit(const WorldGeometry& g, const Ray& ray, uint32_t shape, uint32_t prim) {
  const Shape& s = g.shapes[shape];
  // A moving shape at the ray's time, in double: time * motion added to its time-0 position.
  const D3 offset = {double(ray.time) * s.motion.x, double(ray.time) * s.motion.y, double(ray.time) * s.motion.z};
  const Transform animated = s.animated >= 0 ? g.motions[size_t(s.animated)].at(ray.time) : Transform();
  if (s.kind == ShapeKind::Sphere)
    return exact_sphere(ray, g.spheres[s.index], s.animated >= 0 ? animated : g.spheres[s.index].to_world, offset);
  if (s.kind == ShapeKind::Quadric) return exact_quadric(ray, quadric_at(g, s, ray.time), offset);
  if (s.kind == ShapeKind::Mesh) {
    const TriangleMesh& m = g.meshes[s.index];
    return exact_triangle(ray, to_d(m.vertex(prim, 0)) + offset, to_d(m.vertex(prim, 1)) + offset,
                          to_d(m.vertex(prim, 2)) + offset);
  }
  const MeshInstance& inst = g.instances[s.index];
  const TriangleMesh& m = g.prototypes[inst.prototype];
  const Mat4& xf = (s.animated >= 0 ? animated : inst.to_world).matrix();
  return exact_triangle(ray, apply(xf, to_d(m.vertex(prim, 0)), 1.0) + offset,
                        apply(xf, to_d(m.vertex(prim, 1)), 1.0) + offset,
                        apply(xf, to_d(m.vertex(prim, 2)), 1.0) + offset);
}

}  // namespace kiln
