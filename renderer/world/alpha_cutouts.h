// Alpha cut-outs of a world's shapes (pbrt "alpha"): each shape with one has its opacity, a constant or a float
// texture at the hit's (u, v). The accelerators reach opacity() through WorldGeometry::alpha and apply pbrt-v4's
// stochastic rule (renderer/accel/alpha.h); camera, bounce and shadow rays all go through it there.
//
// Hit coordinates to (u, v): a triangle's barycentrics interpolate its vertices' uv (pbrt's (0,0), (1,0), (1,1)
// when the mesh has none); a quadric's are its (u, v) already. A float image texture is read as pbrt-v4 reads one:
// s = su u + du, t = sv v + dv, the image's row 0 at t = 1 (pbrt flips t), the average of its channels (pbrt's
// bilinear float lookup of an RGB image), decoded by its encoding, times scale, then inverted when asked.
// Texture lookups go through the scene's SceneTextures (renderer/texture/scene_textures.h).
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
  static float opacity(const void* world, uint32_t shape, uint32_t prim, Vec2f hit_uv);

 private:
  float opacity_at(const World& w, uint32_t shape, uint32_t prim, Vec2f hit_uv) const;
  std::vector<int> index_of_shape_;  // shape -> index into alpha_, -1 without one
  std::vector<ShapeAlpha> alpha_;
};

// The opacity of a float image texture `texture` (SceneDesc::textures) at the surface's (u, v), read as above.
float alpha_texture_value(const World& w, int texture, const AlphaImageDesc& image, Vec2f uv);

}  // namespace kiln
