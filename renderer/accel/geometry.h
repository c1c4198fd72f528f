// Geometry as the accelerators see it; the world (renderer/world/world.h) builds it and hands it to them. Shapes live in
// world space except instances, which reference a prototype mesh in object space. A hit names its shape by index
// into WorldGeometry::shapes.
#pragma once
#include <cstdint>
#include <vector>

#include "core/animated_transform.h"
#include "core/bounds.h"
#include "core/quadric.h"
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

// A pbrt disk, cylinder or partial sphere (core/quadric.h) placed by to_world. flip: the surface's normal is the
// opposite of its natural one (pbrt's ReverseOrientation, exclusive-or a transform that mirrors), which makes the
// other side the emitting one.
struct QuadricShape {
  Quadric quadric;
  Transform to_world;
  bool flip = false;
};

enum class ShapeKind : uint8_t { Mesh, Sphere, Instance, Quadric };

// Motion blur, at a ray's time (Ray::time in [0, 1)), in one of two forms; accelerators build time-varying geometry
// for moving shapes only.
//   * translation: a shape with a non-zero motion is translated by time * motion; its mesh, sphere or instance data
//     describe it at time 0 (CENG795 MotionBlur);
//   * animated: a sphere's, quadric's or instance's to_world is WorldGeometry::motions[animated] at the ray's time
//     (pbrt's interpolated transforms); its to_world holds the start transform.
struct Shape {
  ShapeKind kind = ShapeKind::Mesh;
  uint32_t index = 0;  // into meshes (Mesh), spheres (Sphere), instances (Instance) or quadrics (Quadric)
  Vec3f motion{0.0f, 0.0f, 0.0f};
  int32_t animated = -1;
  bool alpha = false;  // has an alpha cut-out: candidate hits go through WorldGeometry::alpha
  bool translates() const { return motion.x != 0.0f || motion.y != 0.0f || motion.z != 0.0f; }
  bool moving() const { return translates() || animated >= 0; }
  Vec3f offset_at(float time) const { return motion * time; }
};

struct MeshInstance {
  uint32_t prototype = 0;  // index into WorldGeometry::prototypes
  Transform to_world;
};

// Alpha cut-outs (pbrt's "alpha"): the accelerators ask the world for the opacity of a shape at a candidate hit,
// given by its primitive and hit coordinates (a triangle's barycentrics b1, b2; a quadric's surface (u, v)) and the
// ray's time (a moving shape is where it is then), and keep the hit by pbrt-v4's stochastic rule
// (renderer/accel/alpha.h). The world evaluates a constant or a texture there; the accelerators know nothing of
// textures.
struct AlphaTest {
  float (*opacity)(const void* world, uint32_t shape, uint32_t prim, Vec2f hit_uv, float time) = nullptr;
  const void* world = nullptr;
};

struct WorldGeometry {
  std::vector<Shape> shapes;
  std::vector<TriangleMesh> meshes;      // world space
  std::vector<SphereShape> spheres;
  std::vector<QuadricShape> quadrics;
  std::vector<TriangleMesh> prototypes;  // object space, used by instances
  std::vector<MeshInstance> instances;
  std::vector<AnimatedTransform> motions;  // the animated shapes' transforms (Shape::animated)
  bool has_motion = false;  // some shape moves: rays carry a time
  AlphaTest alpha;          // set when some shape has Shape::alpha
  Bounds3f bounds() const;  // over the whole shutter interval
  size_t triangle_count() const;  // counting instanced triangles once per instance
};

// The object-to-world transform of a Sphere, Quadric or Instance shape at `time`: its animated transform there, or
// its own to_world (moved by the translation motion's offset).
Transform shape_to_world(const WorldGeometry& g, const Shape& s, float time);
// A Quadric shape placed by its animated transform at `time` (a copy); unanimated, as it is. A translation motion is
// left to the callers, which move the ray back by Shape::offset_at instead.
QuadricShape quadric_at(const WorldGeometry& g, const Shape& s, float time);

}  // namespace kiln
