#include "renderer/texture/bump_map.h"

#include <cmath>

#include "core/frame.h"

namespace kiln {

Vec3f unit_on_side(Vec3f v, Vec3f n) {
  if (!(length_squared(v) > 0.0f) || !is_finite(v)) return n;
  v = normalize(v);
  return dot(v, n) > 0.0f ? v : n;
}

void shading_tangents(Vec3f n, Vec3f dpdu, Vec3f& ss, Vec3f& ts) {
  ss = dpdu - n * dot(n, dpdu);
  ts = cross(n, ss);
  if (!(length_squared(ts) > 0.0f)) coordinate_system(n, ss, ts);
}

Vec3f bump_mapped_normal(const TextureGraph& g, int displacement, const TextureEvalContext& c, Vec3f n, Vec3f dpdu,
                         Vec3f dpdv) {
  float du = 0.5f * (std::fabs(c.fp.dudx) + std::fabs(c.fp.dudy));
  float dv = 0.5f * (std::fabs(c.fp.dvdx) + std::fabs(c.fp.dvdy));
  if (du == 0.0f) du = kBumpDefaultStep;
  if (dv == 0.0f) dv = kBumpDefaultStep;
  TextureEvalContext shifted = c;
  shifted.p = c.p + dpdu * du;
  shifted.uv = c.uv + Vec2f(du, 0.0f);
  const float d_u = g.eval_float(displacement, shifted);
  shifted.p = c.p + dpdv * dv;
  shifted.uv = c.uv + Vec2f(0.0f, dv);
  const float d_v = g.eval_float(displacement, shifted);
  const float d = g.eval_float(displacement, c);
  const Vec3f bumped = cross(dpdu + n * ((d_u - d) / du), dpdv + n * ((d_v - d) / dv));
  return unit_on_side(dot(bumped, n) < 0.0f ? -bumped : bumped, n);
}

Vec3f normal_mapped_normal(const TextureGraph& g, int image, const TextureEvalContext& c, Vec3f n, Vec3f dpdu) {
  TextureEvalContext finest = c;  // normal maps read the finest level whatever the footprint
  finest.dpdx = finest.dpdy = Vec3f(0.0f);
  finest.fp = {};
  const Rgb t = g.eval_rgb(image, finest);
  Vec3f x = dpdu - n * dot(n, dpdu);
  Vec3f y;
  if (length_squared(x) > 0.0f) {
    x = normalize(x);
    y = cross(n, x);
  } else {
    coordinate_system(n, x, y);
  }
  return unit_on_side(x * (2.0f * t.r - 1.0f) + y * (2.0f * t.g - 1.0f) + n * (2.0f * t.b - 1.0f), n);
}

}  // namespace kiln
