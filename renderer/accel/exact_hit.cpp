#include "renderer/accel/exact_hit.h"

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

}  // namespace

ExactHit exact_hit(const WorldGeometry& g, const Ray& ray, uint32_t shape, uint32_t prim) {
  const Shape& s = g.shapes[shape];
  // A moving shape at the ray's time, in double: time * motion added to its time-0 position.
  const D3 offset = {double(ray.time) * s.motion.x, double(ray.time) * s.motion.y, double(ray.time) * s.motion.z};
  const Transform animated = s.animated >= 0 ? g.motions[size_t(s.animated)].at(ray.time) : Transform();
  if (s.kind == ShapeKind::Sphere)
    return exact_sphere(ray, g.spheres[s.index], s.animated >= 0 ? animated : g.spheres[s.index].to_world, offset);
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
