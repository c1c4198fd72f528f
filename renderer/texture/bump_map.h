// Shading normals bent by pbrt-v4 materials' "displacement" (bump mapping) and "normalmap" (pbrt-v4's BumpMap and
// NormalMap, followed by its shading-geometry update).
//
// Bump mapping: the surface is displaced by d(u, v) along its shading normal n; its tangents become
// dp/du + (dd/du) n and dp/dv + (dd/dv) n (dd/du, dd/dv by forward differences of the displacement texture a
// half-footprint along u and v, or 0.0005 without a footprint), and the shading normal their normalised cross product,
// turned to n's side (pbrt-v4 turns the geometric normal instead; for a two-sided surface that is the same). The
// term d dn/du of a curved surface's tangents is left out: it scales both tangents alike on a sphere, and changes the
// normal of a smooth mesh only as far as its normals bend across one displacement height.
//
// Normal maps: the texel's RGB c at (u, 1 - v) (bilinear, finest level, repeated) encodes the unit tangent-space
// normal 2c - 1, in the frame x = dp/du (normalised), z = n, y = z x x.
//
// dpdu / dpdv are the shading tangents: the geometric ones, or for a mesh with vertex normals pbrt-v4's shading
// tangents (dp/du projected onto the shading plane, and n x that).
#pragma once
#include "core/vec.h"
#include "renderer/texture/texture_graph.h"

namespace kiln {

// The step along u and v when the footprint is zero (pbrt-v4's).
inline constexpr float kBumpDefaultStep = 0.0005f;

// The unit shading normal of n's surface displaced by float texture `displacement` of g.
Vec3f bump_mapped_normal(const TextureGraph& g, int displacement, const TextureEvalContext& c, Vec3f n, Vec3f dpdu,
                         Vec3f dpdv);
// The unit shading normal that image texture `image` of g encodes in the tangent frame of (n, dpdu).
Vec3f normal_mapped_normal(const TextureGraph& g, int image, const TextureEvalContext& c, Vec3f n, Vec3f dpdu);
// pbrt-v4's shading tangents of a mesh with vertex normals (see above).
void shading_tangents(Vec3f n, Vec3f dpdu, Vec3f& ss, Vec3f& ts);
// v normalised when it lies on n's side of the surface; n otherwise (a bent normal never turns a surface over).
Vec3f unit_on_side(Vec3f v, Vec3f n);

}  // namespace kiln
