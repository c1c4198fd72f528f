// Generated geometry and ray helpers shared by the accelerator tests.
#pragma once
#include <map>
#include <utility>

#include "core/rng.h"
#include "core/sampling.h"
#include "renderer/accel/accelerator.h"

namespace kiln::test {

// Closed, consistently wound (outward CCW) unit icosahedron subdivided levels times (20 * 4^levels triangles);
// vertices are shared, so the mesh is watertight.
inline TriangleMesh make_icosphere(int levels, Vec3f centre = Vec3f(0.0f), float radius = 1.0f) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Vec3f> p = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                          {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3f& v : p) v = normalize(v);
  std::vector<uint32_t> idx = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      p.push_back(normalize(p[a] + p[b]));
      return mid[key] = uint32_t(p.size() - 1);
    };
    std::vector<uint32_t> next;
    for (size_t i = 0; i < idx.size(); i += 3) {
      const uint32_t a = idx[i], b = idx[i + 1], c = idx[i + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    idx = std::move(next);
  }
  TriangleMesh m;
  for (const Vec3f& v : p) m.p.push_back(centre + v * radius);
  m.idx = std::move(idx);
  return m;
}

// n independent random triangles with vertices inside region, each edge at most max_size long.
inline TriangleMesh make_triangle_soup(size_t n, Rng& rng, Bounds3f region, float max_size) {
  TriangleMesh m;
  const Vec3f ext = region.diagonal();
  for (size_t i = 0; i < n; ++i) {
    const Vec3f base = region.lo + ext * Vec3f(rng.next_float(), rng.next_float(), rng.next_float());
    for (int k = 0; k < 3; ++k) {
      const Vec3f off = (Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) - Vec3f(0.5f)) * max_size;
      m.p.push_back(base + off);
      m.idx.push_back(uint32_t(m.p.size() - 1));
    }
  }
  return m;
}

inline uint32_t add_mesh(WorldGeometry& g, TriangleMesh m) {
  g.meshes.push_back(std::move(m));
  g.shapes.push_back({ShapeKind::Mesh, uint32_t(g.meshes.size() - 1)});
  return uint32_t(g.shapes.size() - 1);
}

inline uint32_t add_sphere(WorldGeometry& g, Vec3f centre, float radius, Transform to_world = {}) {
  g.spheres.push_back({centre, radius, to_world});
  g.shapes.push_back({ShapeKind::Sphere, uint32_t(g.spheres.size() - 1)});
  return uint32_t(g.shapes.size() - 1);
}

inline uint32_t add_prototype(WorldGeometry& g, TriangleMesh m) {
  g.prototypes.push_back(std::move(m));
  return uint32_t(g.prototypes.size() - 1);
}

inline uint32_t add_instance(WorldGeometry& g, uint32_t prototype, Transform to_world) {
  g.instances.push_back({prototype, to_world});
  g.shapes.push_back({ShapeKind::Instance, uint32_t(g.instances.size() - 1)});
  return uint32_t(g.shapes.size() - 1);
}

inline uint32_t add_quadric(WorldGeometry& g, const Quadric& q, Transform to_world = {}, bool flip = false) {
  g.quadrics.push_back({q, to_world, flip});
  g.shapes.push_back({ShapeKind::Quadric, uint32_t(g.quadrics.size() - 1)});
  return uint32_t(g.shapes.size() - 1);
}

// camera_ray(i, rng) at a random instant of the shutter (check-bvh's bounce and shadow rays keep their camera ray's
// time).
template <class CameraRay>
auto at_random_instants(CameraRay camera_ray) {
  return [camera_ray](size_t i, Rng& rng) {
    Ray r = camera_ray(i, rng);
    r.time = rng.next_float();
    return r;
  };
}

inline Vec3f random_in(Rng& rng, const Bounds3f& b) {
  return b.lo + b.diagonal() * Vec3f(rng.next_float(), rng.next_float(), rng.next_float());
}

inline Vec3f random_direction(Rng& rng) { return sample_uniform_sphere(rng.next_2d()); }

// Rays from random points of a box around the scene towards random points of the scene bounds.
inline Ray random_scene_ray(Rng& rng, const Bounds3f& scene) {
  const Vec3f c = scene.center(), half = scene.diagonal() * 1.5f;
  const Vec3f o = random_in(rng, Bounds3f(c - half, c + half));
  return Ray{o, random_in(rng, scene) - o, 0.0f, kInfinity};
}

}  // namespace kiln::test
