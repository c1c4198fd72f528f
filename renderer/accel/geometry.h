// Geometry as the accelerators see it; the world (renderer/world.h) builds it and hands it to them. Shapes live in
// world space except instances, which reference a prototype mesh in object space. A hit names its shape by index
// into WorldGeometry::shapes.
#pragma once
#include <cstdint>
#include <vector>

#include "core/bounds.h"
#include "core/transform.h"

namespace kiln {

struct TriangleMesh {
  std::vector<Vec3f> p;          // positions
  std::vector<uint32_t> idx;     // 3 per triangle
  size_t triangle_count() const { return idx.size() / 3; }
  Vec3f vertex(size_t tri, int k) const { return p[idx[3 * tri + size_t(k)]]; }
};

struct SphereShape {
  Vec3f center;        // in object space of to_world
  float radius = 1.0f;
  Transform to_world;  // identity for plain spheres; non-uniform scale makes an ellipsoid
};

enum class ShapeKind : uint8_t { Mesh, Sphere, Instance };

struct Shape {
  ShapeKind kind = ShapeKind::Mesh;
  uint32_t index = 0;  // into meshes (Mesh), spheres (Sphere) or instances (Instance)
};

struct MeshInstance {
  uint32_t prototype = 0;  // index into WorldGeometry::prototypes
  Transform to_world;
};

struct WorldGeometry {
  std::vector<Shape> shapes;
  std::vector<TriangleMesh> meshes;      // world space
  std::vector<SphereShape> spheres;
  std::vector<TriangleMesh> prototypes;  // object space, used by instances
  std::vector<MeshInstance> instances;
  Bounds3f bounds() const;
  size_t triangle_count() const;  // counting instanced triangles once per instance
};

}  // namespace kiln
