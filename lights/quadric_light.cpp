#include "lights/quadric_light.h"

#include <cmath>

#include "core/error.h"

namespace kiln {
namespace {

// Grid of the area quadrature (per axis of Quadric::sample_area's square) used for non-similarity transforms.
constexpr int kAreaQuadrature = 64;

float det3(const Mat4& m) {
  const auto& a = m.m;
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

}  // namespace

QuadricLight::QuadricLight(const Quadric& quadric, const Transform& to_world, bool flip, Rgb radiance,
                           bool two_sided)
    : quadric_(quadric), to_world_(to_world), flip_(flip), radiance_(radiance), two_sided_(two_sided) {
  abs_det_ = std::abs(det3(to_world.matrix()));
  if (!(abs_det_ > 0.0f) || !std::isfinite(abs_det_))
    throw Error("area light: the shape's transformation is singular (zero scale)");
  // World area = A_obj * mean of J over the object surface; the stratified midpoint rule is exact for J constant.
  double sum = 0.0;
  for (int i = 0; i < kAreaQuadrature; ++i)
    for (int j = 0; j < kAreaQuadrature; ++j) {
      const Vec2f u((float(i) + 0.5f) / kAreaQuadrature, (float(j) + 0.5f) / kAreaQuadrature);
      sum += 1.0 / double(at_object_point(quadric_.sample_area(u)).pdf_area);
    }
  world_area_ = float(sum / (kAreaQuadrature * kAreaQuadrature));
}

QuadricLight::QuadricLight(const Quadric& quadric, const Transform& to_world, bool flip,
                           std::shared_ptr<const EmissionImage> image, bool two_sided)
    : QuadricLight(quadric, to_world, flip, image ? image->mean() : Rgb(0.0f), two_sided) {
  if (!image) throw Error("area light: no emission image");
  image_ = std::move(image);
}

QuadricLight::SurfaceSample QuadricLight::at_object_point(Vec3f p_obj) const {
  const Vec3f m_n = to_world_.normal(quadric_.normal(p_obj));  // M^-T n
  const float len = length(m_n);
  SurfaceSample s;
  s.p = to_world_.point(p_obj);
  s.n = len > 0.0f ? (flip_ ? -m_n : m_n) / len : Vec3f(0.0f, 0.0f, 1.0f);
  s.pdf_area = 1.0f / (quadric_.area() * abs_det_ * len);
  return s;
}

float QuadricLight::solid_angle_pdf(const LightQuery& q, const SurfaceSample& s, Vec3f& wi, float& distance) const {
  const Vec3f to_light = s.p - q.p;
  const float d2 = length_squared(to_light);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return 0.0f;
  distance = std::sqrt(d2);
  wi = to_light / distance;
  const float cos_l = -dot(s.n, wi);  // > 0: q lies on the emitting side of the oriented normal
  if (!(two_sided_ ? std::abs(cos_l) > 0.0f : cos_l > 0.0f)) return 0.0f;
  const float pdf = s.pdf_area * d2 / std::abs(cos_l);
  return std::isfinite(pdf) ? pdf : 0.0f;
}

std::optional<LightSample> QuadricLight::sample_li(const LightQuery& q, Vec2f u) const {
  const Vec3f p_obj = quadric_.sample_area(u);
  const SurfaceSample s = at_object_point(p_obj);
  LightSample ls;
  ls.pdf = solid_angle_pdf(q, s, ls.wi, ls.distance);
  if (!(ls.pdf > 0.0f)) return std::nullopt;
  ls.li = image_ ? image_->radiance(quadric_.uv(p_obj)) : radiance_;
  ls.p_light = s.p;
  ls.n_light = s.n;
  return ls;
}

float QuadricLight::pdf_li(const LightQuery& q, Vec3f p_light, Vec3f, uint32_t) const {
  SurfaceSample s = at_object_point(quadric_.project(to_world_.inverse().point(p_light)));
  s.p = p_light;
  Vec3f wi;
  float distance = 0.0f;
  return solid_angle_pdf(q, s, wi, distance);
}

}  // namespace kiln
