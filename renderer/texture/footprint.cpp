#include "renderer/texture/footprint.h"

#include <algorithm>
#include <cmath>

namespace kiln {
namespace {

// Beyond this many texture periods per pixel a footprint is no longer a useful number (grazing hits): OpenImageIO
// then reads the coarsest level anyway.
constexpr float kMaxUvDerivative = 1e8f;
// A neighbouring ray closer than this to the tangent plane's direction (cosine) does not cross it usefully.
constexpr float kMinCosine = 1e-6f;

// The rotation that takes unit a to unit b (Rodrigues' formula with k = a x b, c = a . b), set up once for the two
// spread vectors it turns.
struct Rotation {
  Vec3f k;
  float c;
  Rotation(Vec3f a, Vec3f b) : k(cross(a, b)), c(dot(a, b)) {}
  Vec3f operator()(Vec3f v) const {
    // b opposite a (a hit behind the camera, met after a bounce): the spread, perpendicular to a, is perpendicular
    // to b as it is; a half turn would only change its sign.
    if (c < -1.0f + 1e-6f) return v;
    return v * c + cross(k, v) + k * (dot(k, v) / (1.0f + c));
  }
};

// Where the ray (o, d) meets the plane through p with normal n, minus p; zero when it runs along the plane.
Vec3f plane_offset(Vec3f o, Vec3f d, Vec3f p, Vec3f n) {
  const float dn = dot(n, d);
  if (std::fabs(dn) < kMinCosine * length(d)) return Vec3f(0.0f);
  const float t = dot(n, p - o) / dn;
  return o + d * t - p;
}

float clamp_derivative(float x) {
  return std::isfinite(x) ? std::clamp(x, -kMaxUvDerivative, kMaxUvDerivative) : 0.0f;
}

}  // namespace

void approximate_dp_dxy(const CameraSpread& c, Vec3f p, Vec3f n, Vec3f& dpdx, Vec3f& dpdy) {
  const Vec3f to_p = p - c.origin;
  const float dist = length(to_p);
  if (!(dist > 0.0f)) {
    dpdx = dpdy = Vec3f(0.0f);
    return;
  }
  const Vec3f dir = to_p / dist;
  // The neighbouring rays as they leave the camera when it looks straight at p.
  const Rotation towards_p(c.axis, dir);
  dpdx = plane_offset(c.origin + c.pos_dx, dir + towards_p(c.dir_dx), p, n);
  dpdy = plane_offset(c.origin + c.pos_dy, dir + towards_p(c.dir_dy), p, n);
}

UvFootprint uv_footprint(Vec3f dpdx, Vec3f dpdy, Vec3f dpdu, Vec3f dpdv) {
  // Normal equations of min |dpdu du + dpdv dv - dpdx|: [A^T A] (du, dv) = A^T dpdx with A = (dpdu dpdv).
  const float a00 = dot(dpdu, dpdu), a01 = dot(dpdu, dpdv), a11 = dot(dpdv, dpdv);
  const float det = a00 * a11 - a01 * a01;
  const float inv = det != 0.0f ? 1.0f / det : 0.0f;
  const float bux = dot(dpdu, dpdx), bvx = dot(dpdv, dpdx), buy = dot(dpdu, dpdy), bvy = dot(dpdv, dpdy);
  UvFootprint f;
  f.dudx = clamp_derivative((a11 * bux - a01 * bvx) * inv);
  f.dvdx = clamp_derivative((a00 * bvx - a01 * bux) * inv);
  f.dudy = clamp_derivative((a11 * buy - a01 * bvy) * inv);
  f.dvdy = clamp_derivative((a00 * bvy - a01 * buy) * inv);
  return f;
}

}  // namespace kiln
