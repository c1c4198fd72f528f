// Alpha cut-outs of a world's shapes (pbrt "alpha"): each shape with one has its opacity, a constant or a float
// texture at the hit's (u, v). The accelerators reach opacity() through WorldGeometry::alpha and apply pbrt-v4's
// stochastic rule (renderer/accel/alpha.h); camera, bounce and shadow rays all go through it there.
//
// A texture sees the hit as a material's textures do (renderer/texture/texture_graph.h): the world-space point and
// normal (of a moving shape, where it is at the ray's time, as pbrt-v4 evaluates alpha), and (u, v) from a triangle's barycentrics and its vertices' uv (pbrt's (0,0), (1,0), (1,1) when the mesh has
// none) or a quadric's own (u, v); every class and mapping, at its finest detail.
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec.h"
#include "scenes/scene.h"

namespace kiln {

struct World;

struct ShapeAlpha {
  ShapeAlphaDesc desc;
  int uvs = -1;  // triangles: index into World::uvs (per-vertex uv of the mesh or instance prototype), or -1
};

class AlphaCutouts {
 public:
  // Records shape `shape`'s cut-out (indices into World::geometry.shapes; set in shape order as the world builds).
  void add(uint32_t shape, ShapeAlpha alpha);
  size_t size() const { return alpha_.size(); }
  bool has(uint32_t shape) const { return shape < index_of_shape_.size() && index_of_shape_[shape] >= 0; }
  // Opacity in [0, 1] of a shape at a candidate hit (AlphaTest's signature; 1 for shapes without a cut-out).
  static float opacity(const void* world, uint32_t shape, uint32_t prim, Vec2f hit_uv, float time);

 private:
  float opacity_at(const World& w, uint32_t shape, uint32_t prim, Vec2f hit_uv, float time) const;
  std::vector<int> index_of_shape_;  // shape -> index into alpha_, -1 without one
  std::vector<ShapeAlpha> alpha_;
};

}  // namespace kiln
