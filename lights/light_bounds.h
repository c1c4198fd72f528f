// What the light hierarchy (lights/light_tree.h) knows of an emitter: where it is, which way it shines and how
// bright it is, and the importance estimate built on them (Conty Estevez & Kulla 2018, "Importance Sampling of Many
// Lights with Adaptive Tree Splitting"; pbrt-v4's LightBounds is the same design).
//   box          world-space bounds of the emitting surface (a single point for point and spot lights)
//   axis         unit direction the cone of emission normals is centred on
//   cos_theta_o  cosine of the half-angle theta_o of that cone of normals (1: one normal; -1: every direction)
//   cos_theta_e  cosine of the angle theta_e beyond the normals over which light still leaves (0, i.e. 90 degrees,
//                for a diffuse surface; the falloff ring of a spot light)
//   phi          peak radiant intensity, a scalar (emission_scale of the RGB): what the emitter sends per unit solid
//                angle towards a point on its axis, L * area for a flat emitter, L * area / 4 (its mean projected
//                area) for a sphere, I for point and spot lights, so importance ~ irradiance for every type alike
//   two_sided    flat emitters that shine from both faces (the cone is then mirrored through the surface)
#pragma once
#include <cstdint>
#include <vector>

#include "core/bounds.h"
#include "lights/light.h"

namespace kiln {

struct LightBounds {
  Bounds3f box;
  Vec3f axis{0.0f, 0.0f, 1.0f};
  float phi = 0.0f;
  float cos_theta_o = 1.0f;
  float cos_theta_e = 1.0f;
  bool two_sided = false;
};

// Bounds of both (box union, the smallest cone holding both cones, the larger theta_e, summed phi).
LightBounds merge(const LightBounds& a, const LightBounds& b);

// The scalar brightness of an RGB emission the hierarchy weighs emitters by: the RGB's root mean square, so a
// saturated blue lamp weighs as much as its contribution to an RGB error (luminance would count it 14x lighter).
inline float emission_scale(Rgb c) { return std::sqrt((c.r * c.r + c.g * c.g + c.b * c.b) / 3.0f); }

// A bounds as the hierarchy evaluates it, with what every evaluation needs precomputed.
struct ImportanceBounds {
  Vec3f center;                // of the box's bounding sphere
  float radius = 0.0f;         // that sphere's radius
  float radius_sq = 0.0f;
  float inside = 0.0f;         // the importance at points inside the sphere: phi / radius^2 (phi for a point)
  Vec3f axis{0.0f, 0.0f, 1.0f};
  float phi = 0.0f;
  float cos_theta_o = 1.0f, sin_theta_o = 0.0f, cos_theta_e = 1.0f;
  // One-sided bounds whose light leaves within 90 degrees of the axis light nothing behind the plane
  // dot(x, axis) = behind_plane through the box's hindmost corner; -infinity for the others.
  float behind_plane = -kInfinity;
  bool two_sided = false;
};
ImportanceBounds importance_bounds(const LightBounds& b);

// An upper-bound style estimate of the light an emitter inside `b` can send to point p (with shading normal n,
// or a zero n when p has none): phi * cos(theta') / d^2 * cos(theta_i'), where theta' and theta_i' are the angles
// between the emission cone and p, and between n and the light, made as small as any point of the bounding sphere
// allows. It is 0 only where no emitter inside b can light p (p outside every direction it shines in), so a
// sampler choosing by it never misses a light that contributes. Points behind every emitter of a one-sided bounds
// (behind_plane) get 0, which the bounding sphere alone would not give points just above a row of lamps.
float importance(const ImportanceBounds& b, Vec3f p, Vec3f n);

// Four bounds side by side (structure of arrays), as a node of the hierarchy holds its children, and their
// importances in one pass of 4-wide SIMD (SSE2, the x86-64 baseline): the same operations as importance() in the
// same order, lane by lane. Lanes that were not set have importance 0 and phi 0.
struct alignas(16) ImportanceBounds4 {
  float center_x[4], center_y[4], center_z[4], radius[4], radius_sq[4], inside[4];
  float axis_x[4], axis_y[4], axis_z[4], phi[4];
  float cos_theta_o[4], sin_theta_o[4], cos_theta_e[4], behind_plane[4];
  uint32_t two_sided[4];  // all bits set: two-sided
  ImportanceBounds4();
  void set(int lane, const ImportanceBounds& b);
};
void importance4(const ImportanceBounds4& b, Vec3f p, Vec3f n, float (&out)[4]);

// One part of a light the hierarchy holds: a whole light, or one triangle of a mesh light (part = its index).
struct EmitterBounds {
  uint32_t light = 0;
  uint32_t part = 0;
  LightBounds bounds;
};

// Appends the parts of light `index` with their bounds: one per triangle of a mesh light (degenerate triangles
// with phi 0), the light itself for other lights with a position. Returns false, appending nothing, for lights at
// infinity (directional, infinite and environment lights), which are sampled beside the hierarchy.
// Every light type has its own case (no default): a new type does not compile until it says how it is bounded.
bool append_emitter_bounds(const Light& light, uint32_t index, std::vector<EmitterBounds>& out);

}  // namespace kiln
