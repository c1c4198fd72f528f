// Where a texture is looked up at a hit: the evaluation context (the hit and its footprint) and the mappings of
// scenes/texture_graph.h, each with its texture-coordinate derivatives per pixel step (pbrt-v4's TextureMapping2D /
// TextureMapping3D).
#pragma once
#include "core/transform.h"
#include "renderer/texture/footprint.h"
#include "scenes/texture_graph.h"

namespace kiln {

// A hit as the textures see it. dpdx / dpdy (and the uv footprint) are zero when nothing needs a footprint: textures
// then read their finest detail.
struct TextureEvalContext {
  Vec3f p;     // world space
  Vec3f n;     // unit geometric normal (directionmix)
  Vec2f uv;
  Vec3f dpdx, dpdy;  // change of p per pixel step along film x and y
  UvFootprint fp;    // change of (u, v) per pixel step
};

// 2-D texture coordinates and their change per pixel step.
struct TexCoord2 {
  Vec2f st;
  float dsdx = 0, dsdy = 0, dtdx = 0, dtdy = 0;
};
// A texture-space point and its change per pixel step.
struct TexCoord3 {
  Vec3f p, dpdx, dpdy;
};

TexCoord2 map_2d(const TextureMappingDesc& m, const TextureEvalContext& c);
TexCoord3 map_3d(const Transform& world_to_texture, const TextureEvalContext& c);

}  // namespace kiln
