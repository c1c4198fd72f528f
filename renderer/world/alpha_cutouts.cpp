#include "renderer/world/alpha_cutouts.h"

#include <algorithm>

#include "renderer/accel/surface_point.h"
#include "renderer/texture/scene_textures.h"
#include "renderer/world/world.h"

namespace kiln {
namespace {

// Where a triangle hit is at `time`, as a texture sees it: the world-space point and unit normal, and the surface
// (u, v) from the vertices' uv or pbrt's default parametrisation.
TextureEvalContext triangle_hit(const World& w, const ShapeAlpha& a, uint32_t shape, uint32_t prim, Vec2f b,
                                float time) {
  const float b0 = 1.0f - b.x - b.y;
  const Shape& s = w.geometry.shapes[shape];
  const TriangleMesh& m = s.kind == ShapeKind::Mesh ? w.geometry.meshes[s.index]
                                                    : w.geometry.prototypes[w.geometry.instances[s.index].prototype];
  const uint32_t* idx = &m.idx[3 * size_t(prim)];
  TextureEvalContext c;
  c.p = m.p[idx[0]] * b0 + m.p[idx[1]] * b.x + m.p[idx[2]] * b.y;
  if (s.kind == ShapeKind::Instance)
    c.p = shape_to_world(w.geometry, s, time).point(c.p);
  else if (s.translates())
    c.p += s.offset_at(time);
  c.n = normalize(triangle_world_normal(w.geometry, shape, prim, time));
  if (a.uvs < 0) {
    c.uv = Vec2f(0.0f, 0.0f) * b0 + Vec2f(1.0f, 0.0f) * b.x + Vec2f(1.0f, 1.0f) * b.y;
  } else {
    const std::vector<Vec2f>& uv = w.uvs[size_t(a.uvs)];
    c.uv = uv[idx[0]] * b0 + uv[idx[1]] * b.x + uv[idx[2]] * b.y;
  }
  return c;
}

// The same for a quadric hit, whose hit coordinates are its (u, v); to_world places it at the ray's time.
TextureEvalContext quadric_hit(const QuadricShape& q, const Transform& to_world, Vec2f uv) {
  TextureEvalContext c;
  const Vec3f p = q.quadric.point_at(uv);
  c.p = to_world.point(p);
  const Vec3f n = normalize(to_world.normal(q.quadric.normal(p)));
  c.n = q.flip ? -n : n;
  c.uv = uv;
  return c;
}

}  // namespace

void AlphaCutouts::add(uint32_t shape, ShapeAlpha alpha) {
  if (index_of_shape_.size() <= shape) index_of_shape_.resize(size_t(shape) + 1, -1);
  index_of_shape_[shape] = int(alpha_.size());
  alpha_.push_back(std::move(alpha));
}

// Textures read the finest detail (no footprint: the test asks about one point of one ray); a texture's value
// outside [0, 1] means fully open or fully opaque, as pbrt-v4's alpha test reads it.
float AlphaCutouts::opacity_at(const World& w, uint32_t shape, uint32_t prim, Vec2f hit_uv, float time) const {
  const int i = shape < index_of_shape_.size() ? index_of_shape_[shape] : -1;
  if (i < 0) return 1.0f;
  const ShapeAlpha& a = alpha_[size_t(i)];
  if (a.desc.texture < 0) return a.desc.value;
  const Shape& s = w.geometry.shapes[shape];
  const TextureEvalContext c =
      s.kind == ShapeKind::Quadric
          ? quadric_hit(w.geometry.quadrics[s.index], shape_to_world(w.geometry, s, time), hit_uv)
          : triangle_hit(w, a, shape, prim, hit_uv, time);
  return w.textures->graph().eval_float(a.desc.texture, c);
}

float AlphaCutouts::opacity(const void* world, uint32_t shape, uint32_t prim, Vec2f hit_uv, float time) {
  const World& w = *static_cast<const World*>(world);
  return w.alpha->opacity_at(w, shape, prim, hit_uv, time);
}

}  // namespace kiln
