#include "renderer/texture/texture_mapping.h"

#include <cmath>

#include "core/math.h"

namespace kiln {
namespace {

// s and t as linear functions of the texture-space point near it: their derivatives along the footprint.
TexCoord2 with_gradients(Vec2f st, Vec3f ds_dp, Vec3f dt_dp, Vec3f dpdx, Vec3f dpdy) {
  return {st, dot(ds_dp, dpdx), dot(ds_dp, dpdy), dot(dt_dp, dpdx), dot(dt_dp, dpdy)};
}

// theta / pi from +z and phi / 2 pi in [0, 1) of the point's direction from the origin; their gradients in p.
TexCoord2 spherical(const TexCoord3& c) {
  const Vec3f p = c.p;
  const float r2xy = p.x * p.x + p.y * p.y, rxy = std::sqrt(r2xy), r2 = r2xy + p.z * p.z;
  const float len = std::sqrt(r2);
  if (!(len > 0.0f)) return {};
  const float theta = std::acos(std::clamp(p.z / len, -1.0f, 1.0f));
  float phi = std::atan2(p.y, p.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  // d phi / dp = (-y, x, 0) / (x^2 + y^2); d theta / dp = (x z / rxy, y z / rxy, -rxy) / r^2.
  const Vec3f ds_dp = r2xy > 0.0f ? Vec3f(-p.y, p.x, 0.0f) / (2.0f * kPi * r2xy) : Vec3f(0.0f);
  const Vec3f dt_dp = rxy > 0.0f ? Vec3f(p.x * p.z / rxy, p.y * p.z / rxy, -rxy) / (kPi * r2) : Vec3f(0.0f);
  return with_gradients({theta / kPi, phi / (2.0f * kPi)}, ds_dp, dt_dp, c.dpdx, c.dpdy);
}

TexCoord2 cylindrical(const TexCoord3& c) {
  const Vec3f p = c.p;
  const float r2xy = p.x * p.x + p.y * p.y;
  const Vec3f ds_dp = r2xy > 0.0f ? Vec3f(-p.y, p.x, 0.0f) / (2.0f * kPi * r2xy) : Vec3f(0.0f);
  return with_gradients({(kPi + std::atan2(p.y, p.x)) / (2.0f * kPi), p.z}, ds_dp, Vec3f(0, 0, 1), c.dpdx, c.dpdy);
}

}  // namespace

TexCoord3 map_3d(const Transform& world_to_texture, const TextureEvalContext& c) {
  return {world_to_texture.point(c.p), world_to_texture.vector(c.dpdx), world_to_texture.vector(c.dpdy)};
}

TexCoord2 map_2d(const TextureMappingDesc& m, const TextureEvalContext& c) {
  switch (m.kind) {
    case TextureMapping::Uv:
      return {{m.su * c.uv.x + m.du, m.sv * c.uv.y + m.dv},
              m.su * c.fp.dudx, m.su * c.fp.dudy, m.sv * c.fp.dvdx, m.sv * c.fp.dvdy};
    case TextureMapping::Spherical: return spherical(map_3d(m.world_to_texture, c));
    case TextureMapping::Cylindrical: return cylindrical(map_3d(m.world_to_texture, c));
    case TextureMapping::Planar: {
      const TexCoord3 t = map_3d(m.world_to_texture, c);
      return with_gradients({m.du + dot(t.p, m.v1), m.dv + dot(t.p, m.v2)}, m.v1, m.v2, t.dpdx, t.dpdy);
    }
  }
  return {};
}

}  // namespace kiln
