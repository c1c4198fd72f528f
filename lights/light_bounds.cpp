#include "lights/light_bounds.h"

#include <immintrin.h>  // SSE2: part of the x86-64 baseline

namespace kiln {
namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

// The cone of directions every emission direction of an emitter lies in: its axis and the cosine of its half-angle.
struct Cone {
  Vec3f w;
  float cos_theta;
};

// Angle between unit vectors, accurate near 0 and pi as well (where acos of the dot product is not).
float angle_between(Vec3f a, Vec3f b) {
  if (dot(a, b) < 0.0f) return kPi - 2.0f * safe_asin(length(a + b) * 0.5f);
  return 2.0f * safe_asin(length(b - a) * 0.5f);
}

// The smallest cone holding both cones.
Cone merge_cones(Cone a, Cone b) {
  const Cone sphere{a.w, -1.0f};
  if (a.cos_theta <= -1.0f || b.cos_theta <= -1.0f) return sphere;
  const float theta_a = safe_acos(a.cos_theta), theta_b = safe_acos(b.cos_theta);
  const float theta_d = angle_between(a.w, b.w);
  if (std::min(theta_d + theta_b, kPi) <= theta_a) return a;
  if (std::min(theta_d + theta_a, kPi) <= theta_b) return b;
  const float theta_o = 0.5f * (theta_a + theta_d + theta_b);
  if (theta_o >= kPi) return sphere;
  // Turn a's axis towards b's by the angle that puts both far edges on the new cone.
  const Vec3f k = cross(a.w, b.w);
  const float k_len = length(k);
  if (!(k_len > 0.0f)) return sphere;  // opposite axes
  const float theta_r = theta_o - theta_a;
  const Vec3f w = a.w * std::cos(theta_r) + cross(k / k_len, a.w) * std::sin(theta_r);
  return {normalize(w), std::cos(theta_o)};
}

// A flat emitter (triangle or parallelogram) of area `area` with unit normal n.
LightBounds flat_bounds(Bounds3f box, Vec3f n, float area, Rgb radiance, bool two_sided) {
  LightBounds b;
  b.box = box;
  b.axis = n;
  b.phi = emission_scale(radiance) * area;
  b.cos_theta_o = 1.0f;
  b.cos_theta_e = 0.0f;  // diffuse: light leaves up to 90 degrees from the normal
  b.two_sided = two_sided;
  return b;
}

// An emitter at one point that shines in every direction (theta_o = pi).
LightBounds omni_bounds(Bounds3f box, float phi) {
  LightBounds b;
  b.box = box;
  b.phi = phi;
  b.cos_theta_o = -1.0f;
  b.cos_theta_e = 0.0f;
  return b;
}

LightBounds spot_bounds(const SpotLight& l) {
  LightBounds b;
  b.box = Bounds3f(l.position());
  b.axis = l.direction();
  b.phi = emission_scale(l.intensity());
  b.cos_theta_o = l.cos_falloff();
  // The falloff ring reaches theta_coverage - theta_falloff beyond the full-intensity cone.
  b.cos_theta_e = std::cos(safe_acos(l.cos_coverage()) - safe_acos(l.cos_falloff()));
  return b;
}

void append_triangles(const MeshLight& m, uint32_t index, std::vector<EmitterBounds>& out) {
  for (size_t i = 0; i < m.triangle_count(); ++i) {
    const auto p = m.triangle(i);
    Bounds3f box(p[0], p[1]);
    box.extend(p[2]);
    out.push_back({index, uint32_t(i),
                   flat_bounds(box, m.triangle_normal(i), m.triangle_area(i), m.radiance(), m.two_sided())});
  }
}

LightBounds area_light_bounds(const AreaLight& l) {
  Bounds3f box(l.corner(), l.corner() + l.edge1());
  box.extend(l.corner() + l.edge2());
  box.extend(l.corner() + l.edge1() + l.edge2());
  return flat_bounds(box, l.normal(), l.area(), l.radiance(), true);
}

// Relative margin of behind_plane (several float roundings of a three-term dot product).
constexpr float kPlaneSlack = 1e-6f;
// Beyond 90 degrees (a spot light's wide falloff ring) the emission does not follow a cosine: it stays positive.
constexpr float kRingFloor = 1e-3f;

}  // namespace

LightBounds merge(const LightBounds& a, const LightBounds& b) {
  if (!(a.phi > 0.0f)) return b;
  if (!(b.phi > 0.0f)) return a;
  const Cone c = merge_cones({a.axis, a.cos_theta_o}, {b.axis, b.cos_theta_o});
  LightBounds m;
  m.box = kiln::merge(a.box, b.box);
  m.axis = c.w;
  m.cos_theta_o = c.cos_theta;
  m.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  m.phi = a.phi + b.phi;
  m.two_sided = a.two_sided || b.two_sided;
  return m;
}

ImportanceBounds importance_bounds(const LightBounds& b) {
  ImportanceBounds ib;
  ib.center = b.box.center();
  ib.radius = length(b.box.diagonal() * 0.5f);
  ib.radius_sq = ib.radius * ib.radius;
  ib.inside = ib.radius_sq > 0.0f ? b.phi / ib.radius_sq : b.phi;
  ib.axis = b.axis;
  ib.phi = b.phi;
  ib.cos_theta_o = b.cos_theta_o;
  ib.sin_theta_o = safe_sqrt(1.0f - b.cos_theta_o * b.cos_theta_o);
  ib.cos_theta_e = b.cos_theta_e;
  ib.two_sided = b.two_sided;
  // theta_o + theta_e <= 90 degrees: every emission direction d has dot(d, axis) >= 0.
  if (!b.two_sided && safe_acos(b.cos_theta_o) + safe_acos(b.cos_theta_e) <= 0.5f * kPi) {
    const Vec3f a = b.axis;
    const float plane = std::min(a.x * b.box.lo.x, a.x * b.box.hi.x) + std::min(a.y * b.box.lo.y, a.y * b.box.hi.y) +
                        std::min(a.z * b.box.lo.z, a.z * b.box.hi.z);
    // Moved back by a few roundings of the sum, so that no point in front of an emitter falls behind it.
    ib.behind_plane = plane - kPlaneSlack * (std::abs(plane) + length(b.box.diagonal()));
  }
  return ib;
}

float importance(const ImportanceBounds& b, Vec3f p, Vec3f n) {
  if (dot(p, b.axis) <= b.behind_plane) return 0.0f;
  const Vec3f to_p = p - b.center;
  const float d2 = length_squared(to_p);
  // Inside the bounding sphere every direction and distance is possible: the estimate of a point on its surface.
  if (d2 <= b.radius_sq) return b.inside;
  const float inv_d = 1.0f / std::sqrt(d2), inv_d2 = inv_d * inv_d;
  const Vec3f wi = to_p * inv_d;  // from the emitter towards p
  // theta_b: half-angle of the cone the bounding sphere subtends from p.
  const float sin_b = b.radius * inv_d, cos_b = safe_sqrt(1.0f - sin_b * sin_b);
  // theta' = max(0, theta_w - theta_o - theta_b): the smallest angle between an emission normal and p.
  float cos_w = dot(b.axis, wi);
  if (b.two_sided) cos_w = std::abs(cos_w);
  const float sin_w = safe_sqrt(1.0f - cos_w * cos_w);
  float cos_x = 1.0f, sin_x = 0.0f;  // theta_x = max(0, theta_w - theta_o)
  if (cos_w < b.cos_theta_o) {
    cos_x = cos_w * b.cos_theta_o + sin_w * b.sin_theta_o;
    sin_x = sin_w * b.cos_theta_o - cos_w * b.sin_theta_o;
  }
  const float cos_p = cos_x < cos_b ? cos_x * cos_b + sin_x * sin_b : 1.0f;
  if (cos_p < b.cos_theta_e) return 0.0f;
  float imp = b.phi * std::max(cos_p, kRingFloor) * inv_d2;
  if (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f) {
    // theta_i' = max(0, theta_i - theta_b), theta_i from either side of the surface (it may transmit).
    const float cos_i = std::abs(dot(wi, n));
    if (cos_i < cos_b) imp *= cos_i * cos_b + safe_sqrt(1.0f - cos_i * cos_i) * sin_b;
  }
  return imp;
}

ImportanceBounds4::ImportanceBounds4() {
  for (int k = 0; k < 4; ++k) {
    center_x[k] = center_y[k] = center_z[k] = radius[k] = radius_sq[k] = inside[k] = 0.0f;
    axis_x[k] = axis_y[k] = 0.0f;
    axis_z[k] = 1.0f;
    phi[k] = 0.0f;
    cos_theta_o[k] = cos_theta_e[k] = 1.0f;
    sin_theta_o[k] = 0.0f;
    behind_plane[k] = kInfinity;  // every point is behind an unused lane: importance 0
    two_sided[k] = 0;
  }
}

void ImportanceBounds4::set(int lane, const ImportanceBounds& b) {
  const size_t k = size_t(lane);
  center_x[k] = b.center.x;
  center_y[k] = b.center.y;
  center_z[k] = b.center.z;
  radius[k] = b.radius;
  radius_sq[k] = b.radius_sq;
  inside[k] = b.inside;
  axis_x[k] = b.axis.x;
  axis_y[k] = b.axis.y;
  axis_z[k] = b.axis.z;
  phi[k] = b.phi;
  cos_theta_o[k] = b.cos_theta_o;
  sin_theta_o[k] = b.sin_theta_o;
  cos_theta_e[k] = b.cos_theta_e;
  behind_plane[k] = b.behind_plane;
  two_sided[k] = b.two_sided ? 0xffffffffu : 0u;
}

namespace {

__m128 dot4(__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
  return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
}
__m128 select4(__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); }
__m128 abs4(__m128 x) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), x); }
// sqrt(max(0, 1 - x^2)): the sine of an angle from its cosine.
__m128 sine4(__m128 cos) {
  return _mm_sqrt_ps(_mm_max_ps(_mm_setzero_ps(), _mm_sub_ps(_mm_set1_ps(1.0f), _mm_mul_ps(cos, cos))));
}
// cos(a - b) from cosines and sines, where a > b (cos a < cos b), else 1: the cosine of max(0, a - b).
__m128 cos_minus4(__m128 cos_a, __m128 sin_a, __m128 cos_b, __m128 sin_b) {
  return select4(_mm_cmplt_ps(cos_a, cos_b), _mm_add_ps(_mm_mul_ps(cos_a, cos_b), _mm_mul_ps(sin_a, sin_b)),
                 _mm_set1_ps(1.0f));
}

}  // namespace

void importance4(const ImportanceBounds4& b, Vec3f p, Vec3f n, float (&out)[4]) {
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  const __m128 px = _mm_set1_ps(p.x), py = _mm_set1_ps(p.y), pz = _mm_set1_ps(p.z);
  const __m128 ax = _mm_load_ps(b.axis_x), ay = _mm_load_ps(b.axis_y), az = _mm_load_ps(b.axis_z);
  const __m128 alive = _mm_cmpnle_ps(dot4(px, py, pz, ax, ay, az), _mm_load_ps(b.behind_plane));
  const __m128 tx = _mm_sub_ps(px, _mm_load_ps(b.center_x)), ty = _mm_sub_ps(py, _mm_load_ps(b.center_y)),
               tz = _mm_sub_ps(pz, _mm_load_ps(b.center_z));
  const __m128 d2 = dot4(tx, ty, tz, tx, ty, tz);
  const __m128 inside = _mm_cmple_ps(d2, _mm_load_ps(b.radius_sq));
  const __m128 inv_d = _mm_div_ps(one, _mm_sqrt_ps(d2)), inv_d2 = _mm_mul_ps(inv_d, inv_d);
  const __m128 wx = _mm_mul_ps(tx, inv_d), wy = _mm_mul_ps(ty, inv_d), wz = _mm_mul_ps(tz, inv_d);
  const __m128 sin_b = _mm_mul_ps(_mm_load_ps(b.radius), inv_d), cos_b = sine4(sin_b);
  __m128 cos_w = dot4(ax, ay, az, wx, wy, wz);
  cos_w = select4(_mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(b.two_sided))), abs4(cos_w), cos_w);
  const __m128 sin_w = sine4(cos_w);
  const __m128 cos_o = _mm_load_ps(b.cos_theta_o), sin_o = _mm_load_ps(b.sin_theta_o);
  const __m128 beyond_o = _mm_cmplt_ps(cos_w, cos_o);
  const __m128 cos_x = select4(beyond_o, _mm_add_ps(_mm_mul_ps(cos_w, cos_o), _mm_mul_ps(sin_w, sin_o)), one);
  const __m128 sin_x = select4(beyond_o, _mm_sub_ps(_mm_mul_ps(sin_w, cos_o), _mm_mul_ps(cos_w, sin_o)), zero);
  const __m128 cos_p = cos_minus4(cos_x, sin_x, cos_b, sin_b);
  const __m128 lit = _mm_cmpnlt_ps(cos_p, _mm_load_ps(b.cos_theta_e));
  __m128 imp = _mm_mul_ps(_mm_mul_ps(_mm_load_ps(b.phi), _mm_max_ps(cos_p, _mm_set1_ps(kRingFloor))), inv_d2);
  if (n.x != 0.0f || n.y != 0.0f || n.z != 0.0f) {
    const __m128 cos_i = abs4(dot4(wx, wy, wz, _mm_set1_ps(n.x), _mm_set1_ps(n.y), _mm_set1_ps(n.z)));
    imp = _mm_mul_ps(imp, cos_minus4(cos_i, sine4(cos_i), cos_b, sin_b));
  }
  const __m128 value = select4(inside, _mm_load_ps(b.inside), _mm_and_ps(lit, imp));
  _mm_store_ps(out, _mm_and_ps(alive, value));
}

bool append_emitter_bounds(const Light& light, uint32_t index, std::vector<EmitterBounds>& out) {
  const auto whole = [&](const LightBounds& b) {
    out.push_back({index, kWholeLight, b});
    return true;
  };
  return std::visit(
      Overloaded{
          [&](const PointLight& l) { return whole(omni_bounds(Bounds3f(l.position()), emission_scale(l.intensity()))); },
          [&](const SpotLight& l) { return whole(spot_bounds(l)); },
          [&](const AreaLight& l) { return whole(area_light_bounds(l)); },
          [&](const MeshLight& l) {
            append_triangles(l, index, out);
            return true;
          },
          // Its mean projected area is a quarter of its surface (Cauchy): phi is L * area / 4 in every direction.
          [&](const SphereLight& l) {
            return whole(omni_bounds(l.world_bounds(), emission_scale(l.radiance()) * l.surface_area() * 0.25f));
          },
          // Bounded as if it emitted in every direction (a disk's or cylinder's normal cone is not tracked): averaged
          // over all directions, its projected area is a quarter of its area per emitting side.
          [&](const QuadricLight& l) {
            const float sides = l.two_sided() ? 2.0f : 1.0f;
            return whole(omni_bounds(l.to_world().bounds(l.quadric().bounds()),
                                     emission_scale(l.radiance()) * l.area() * 0.25f * sides));
          },
          [](const DirectionalLight&) { return false; },
          [](const InfiniteLight&) { return false; },
          [](const ImageInfiniteLight&) { return false; },
      },
      light);
}

}  // namespace kiln
