#include "renderer/world/alpha_cutouts.h"

#include <algorithm>

#include "renderer/texture/scene_textures.h"
#include "renderer/world/world.h"

namespace kiln {
namespace {

// The surface (u, v) of a triangle hit: its vertices' uv, or pbrt's default parametrisation.
Vec2f triangle_uv(const World& w, const ShapeAlpha& a, uint32_t shape, uint32_t prim, Vec2f b) {
  const float b0 = 1.0f - b.x - b.y;
  if (a.uvs < 0) return Vec2f(0.0f, 0.0f) * b0 + Vec2f(1.0f, 0.0f) * b.x + Vec2f(1.0f, 1.0f) * b.y;
  const Shape& s = w.geometry.shapes[shape];
  const TriangleMesh& m = s.kind == ShapeKind::Mesh ? w.geometry.meshes[s.index]
                                                    : w.geometry.prototypes[w.geometry.instances[s.index].prototype];
  const uint32_t* idx = &m.idx[3 * size_t(prim)];
  const std::vector<Vec2f>& uv = w.uvs[size_t(a.uvs)];
  return uv[idx[0]] * b0 + uv[idx[1]] * b.x + uv[idx[2]] * b.y;
}

float decoded(float v, const AlphaImageDesc& image) {
  switch (image.encoding) {
    case AlphaEncoding::Linear: return v;
    case AlphaEncoding::Srgb: return srgb_to_linear(std::clamp(v, 0.0f, 1.0f));
    case AlphaEncoding::Gamma: return std::pow(std::max(v, 0.0f), image.gamma);
  }
  return v;
}

}  // namespace

void AlphaCutouts::add(uint32_t shape, ShapeAlpha alpha) {
  if (index_of_shape_.size() <= shape) index_of_shape_.resize(size_t(shape) + 1, -1);
  index_of_shape_[shape] = int(alpha_.size());
  alpha_.push_back(std::move(alpha));
}

float alpha_texture_value(const World& w, int texture, const AlphaImageDesc& image, Vec2f uv) {
  const Vec2f st(image.su * uv.x + image.du, 1.0f - (image.sv * uv.y + image.dv));
  const float v = decoded(w.textures->value(texture, st, Vec3f(0.0f)).average(), image) * image.scale;
  return image.invert ? std::max(0.0f, 1.0f - v) : v;
}

float AlphaCutouts::opacity_at(const World& w, uint32_t shape, uint32_t prim, Vec2f hit_uv) const {
  const int i = shape < index_of_shape_.size() ? index_of_shape_[shape] : -1;
  if (i < 0) return 1.0f;
  const ShapeAlpha& a = alpha_[size_t(i)];
  if (a.desc.texture < 0) return a.desc.value;
  const bool triangles = w.geometry.shapes[shape].kind != ShapeKind::Quadric;
  const Vec2f uv = triangles ? triangle_uv(w, a, shape, prim, hit_uv) : hit_uv;
  return alpha_texture_value(w, a.desc.texture, a.desc.image, uv);
}

float AlphaCutouts::opacity(const void* world, uint32_t shape, uint32_t prim, Vec2f hit_uv) {
  const World& w = *static_cast<const World*>(world);
  return w.alpha->opacity_at(w, shape, prim, hit_uv);
}

}  // namespace kiln
