#include "materials/trowbridge_reitz.h"

namespace kiln {
namespace {

// Heitz's hemisphere-projection warp keeps the sampled normal strictly above the horizon by this much.
constexpr float kMinSampledNormalZ = 1e-6f;
// Above this cos(theta) the visible hemisphere's tangent frame falls back to the x axis.
constexpr float kFrameFallbackCos = 0.99999f;

}  // namespace

TrowbridgeReitz::TrowbridgeReitz(float ax, float ay) : alpha_x(ax), alpha_y(ay) {
  if (!effectively_smooth()) {
    alpha_x = std::max(alpha_x, kMinAlpha);
    alpha_y = std::max(alpha_y, kMinAlpha);
  }
}

float TrowbridgeReitz::roughness_to_alpha(float roughness) { return std::sqrt(std::max(0.0f, roughness)); }

float TrowbridgeReitz::d(Vec3f wm) const {
  // The stretched form of 1 / (pi ax ay cos^4 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2), which needs
  // no tangent and stays finite at the horizon.
  const float s = sqr(wm.x / alpha_x) + sqr(wm.y / alpha_y) + sqr(wm.z);
  return 1.0f / (kPi * alpha_x * alpha_y * s * s);
}

float TrowbridgeReitz::lambda(Vec3f w) const {
  const float z2 = w.z * w.z;
  if (z2 == 0.0f) return kInfinity;
  const float a2_tan2 = (sqr(alpha_x * w.x) + sqr(alpha_y * w.y)) / z2;
  if (!std::isfinite(a2_tan2)) return kInfinity;
  // (sqrt(1 + t) - 1) / 2 without the cancellation for small t.
  return 0.5f * a2_tan2 / (std::sqrt(1.0f + a2_tan2) + 1.0f);
}

float TrowbridgeReitz::visible_d(Vec3f w, Vec3f wm) const {
  if (w.z == 0.0f) return 0.0f;
  // Only normals facing w's side are visible: w . wm has the sign of w.z.
  const float cos_wm = w.z > 0.0f ? dot(w, wm) : -dot(w, wm);
  if (!(cos_wm > 0.0f)) return 0.0f;
  return g1(w) / std::abs(w.z) * d(wm) * cos_wm;
}

Vec3f TrowbridgeReitz::sample_visible(Vec3f w, Vec2f u) const {
  // Stretch w into the configuration where the distribution is the unit hemisphere, on the side w views.
  Vec3f wh = normalize(Vec3f(alpha_x * w.x, alpha_y * w.y, w.z));
  if (wh.z < 0.0f) wh = -wh;
  const Vec3f t1 = wh.z < kFrameFallbackCos ? normalize(Vec3f(-wh.y, wh.x, 0.0f)) : Vec3f(1.0f, 0.0f, 0.0f);
  const Vec3f t2 = cross(wh, t1);
  // Uniform point on the disk (polar map), squeezed onto the part of the projected hemisphere visible from wh.
  const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
  const float px = r * std::cos(phi);
  float py = r * std::sin(phi);
  const float h = safe_sqrt(1.0f - px * px);
  const float s = 0.5f * (1.0f + wh.z);
  py = (1.0f - s) * h + s * py;
  const float pz = safe_sqrt(1.0f - px * px - py * py);
  const Vec3f nh = px * t1 + py * t2 + pz * wh;
  // Unstretch back to the ellipsoid configuration.
  return normalize(Vec3f(alpha_x * nh.x, alpha_y * nh.y, std::max(kMinSampledNormalZ, nh.z)));
}

}  // namespace kiln
