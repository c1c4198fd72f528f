#include "lights/image_infinite_light.h"

#include <algorithm>
#include <cmath>

#include "core/equal_area.h"
#include "core/error.h"
#include "core/frame.h"

namespace kiln {
namespace {

// Shadow-ray targets sit this many scene radii from the query point (outside every object), as for InfiniteLight.
constexpr float kTargetDistanceRadii = 2.0f;

bool has_normal(const LightQuery& q) { return length_squared(q.n) > 0.0f; }

Rgb usable(Rgb c) {
  for (int i = 0; i < 3; ++i)
    if (!(c[i] > 0.0f) || !std::isfinite(c[i])) c[i] = 0.0f;
  return c;
}

using Mat3 = std::array<float, 9>;
Mat3 linear_part(const Mat4& m) {
  Mat3 a{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[size_t(3 * r + c)] = m.m[size_t(r)][size_t(c)];
  return a;
}
Vec3f apply(const Mat3& m, Vec3f v) {
  return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
          m[6] * v.x + m[7] * v.y + m[8] * v.z};
}
float det(const Mat3& m) {
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
}

}  // namespace

Vec3f ImageInfiniteLight::direction(float u, float v) {
  const float phi = kPi * (2.0f * u - 1.0f), theta = kPi * v;
  const float st = std::sin(theta);
  return {st * std::sin(phi), std::cos(theta), -st * std::cos(phi)};
}

Vec2f ImageInfiniteLight::lat_long(Vec3f d) {
  const float u = 0.5f * (1.0f + std::atan2(d.x, -d.z) * kInvPi);
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) * kInvPi;
  return {u, v};
}

Vec3f ImageInfiniteLight::map_direction(Vec2f uv) const {
  return layout_ == EnvMapLayout::EqualArea ? equal_area_square_to_sphere(uv) : direction(uv.x, uv.y);
}

Vec2f ImageInfiniteLight::map_coordinates(Vec3f d) const {
  return layout_ == EnvMapLayout::EqualArea ? equal_area_sphere_to_square(d) : lat_long(d);
}

Vec3f ImageInfiniteLight::to_world(Vec3f m) const { return placed_ ? normalize(apply(to_world_, m)) : m; }
Vec3f ImageInfiniteLight::to_map(Vec3f w) const { return placed_ ? normalize(apply(to_map_, w)) : w; }

ImageInfiniteLight::ImageInfiniteLight(Image image, float scene_radius, EnvMapSampling sampling,
                                       const EnvMapPlacement& placement)
    : image_(std::move(image)), scene_radius_(scene_radius), sampling_(sampling), layout_(placement.layout) {
  if (image_.width() <= 0 || image_.height() <= 0) throw Error("environment map: the image is empty");
  if (layout_ == EnvMapLayout::EqualArea && image_.width() != image_.height())
    throw Error("environment map: an equal-area map must be square, this one is " + std::to_string(image_.width()) +
                " x " + std::to_string(image_.height()));
  if (!(scene_radius > 0.0f) || !std::isfinite(scene_radius))
    throw Error("environment light: the scene radius must be positive");
  placed_ = !placement.light_to_world.is_identity();
  to_world_ = linear_part(placement.light_to_world.matrix());
  to_map_ = linear_part(placement.light_to_world.inverse_matrix());
  abs_det_ = std::abs(det(to_world_));
  if (!(abs_det_ > 0.0f) || !std::isfinite(abs_det_))
    throw Error("environment light: its transformation is singular");
  for (Rgb& c : image_.pixels()) c = usable(c);
  const int w = image_.width(), h = image_.height();
  const bool equal_area = layout_ == EnvMapLayout::EqualArea;
  std::vector<float> row_weights(static_cast<size_t>(h)), texel_weights(static_cast<size_t>(w));
  columns_.reserve(size_t(h));
  for (int y = 0; y < h; ++y) {
    const float sin_theta = equal_area ? 1.0f : std::sin(kPi * (float(y) + 0.5f) / float(h));
    double row = 0.0, row_luminance = 0.0;
    for (int x = 0; x < w; ++x) {
      texel_weights[size_t(x)] = image_.at(x, y).luminance() * sin_theta;
      row += texel_weights[size_t(x)];
      row_luminance += image_.at(x, y).luminance();
    }
    columns_.emplace_back(texel_weights);
    row_weights[size_t(y)] = float(row);
    // The solid angle of one texel of this row: 4 pi / (w h) on the equal-area square; on the lat-long map
    // (2 pi / w) (cos theta_top - cos theta_bottom).
    const double texel_solid_angle = equal_area ? 4.0 * kPi / (double(w) * h)
                                                : (2.0 * kPi / w) * (std::cos(kPi * double(y) / h) -
                                                                     std::cos(kPi * double(y + 1) / h));
    radiant_integral_ += row_luminance * texel_solid_angle;
  }
  rows_ = Distribution1D(row_weights);
}

ImageInfiniteLight::Texel ImageInfiniteLight::texel(Vec2f uv) const {
  const int w = image_.width(), h = image_.height();
  int x = int(uv.x * float(w)), y = int(uv.y * float(h));
  if (layout_ == EnvMapLayout::EqualArea) {
    wrap_octahedral(x, y, w, h);
    return {x, y};
  }
  return {std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1)};
}

Rgb ImageInfiniteLight::radiance(Vec3f d) const {
  const Texel t = texel(map_coordinates(to_map(d)));
  return image_.at(t.x, t.y);
}

float ImageInfiniteLight::solid_angle_density(float p_uv, Vec3f m) const {
  if (layout_ == EnvMapLayout::EqualArea) return p_uv * kInv4Pi;
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - m.y * m.y));
  return sin_theta > 0.0f ? p_uv / (2.0f * kPi * kPi * sin_theta) : 0.0f;
}

// The map-frame direction m = normalize(L^-1 w) of a world direction w has density p_world(w) = p_map(m) /
// (|det L| |L^-1 w|^3).
float ImageInfiniteLight::placement_jacobian(Vec3f wi) const {
  if (!placed_) return 1.0f;
  const float l = length(apply(to_map_, wi));
  return 1.0f / (abs_det_ * l * l * l);
}

float ImageInfiniteLight::importance_pdf(Vec3f wi) const {
  const Vec3f m = to_map(wi);
  const Texel t = texel(map_coordinates(m));
  const float p_uv = rows_.pmf(size_t(t.y)) * columns_[size_t(t.y)].pmf(size_t(t.x)) * float(image_.width()) *
                     float(image_.height());
  return solid_angle_density(p_uv, m) * placement_jacobian(wi);
}

std::optional<LightSample> ImageInfiniteLight::sample_li(const LightQuery& q, Vec2f u) const {
  LightSample s;
  if (sampling_ == EnvMapSampling::ImportanceSampled) {
    float row_pmf = 0.0f, column_pmf = 0.0f, v_in = 0.0f, u_in = 0.0f;
    const size_t y = rows_.sample(u.y, &row_pmf, &v_in);
    if (!(row_pmf > 0.0f)) return std::nullopt;
    const size_t x = columns_[y].sample(u.x, &column_pmf, &u_in);
    if (!(column_pmf > 0.0f)) return std::nullopt;
    const Vec2f uv((float(x) + u_in) / float(image_.width()), (float(y) + v_in) / float(image_.height()));
    const Vec3f m = map_direction(uv);
    s.wi = to_world(m);
    // The chosen texel's density: what pdf_direction gives wi (it maps wi back to the same texel, except within
    // float rounding of a texel edge).
    const float p_uv = row_pmf * column_pmf * float(image_.width()) * float(image_.height());
    s.pdf = solid_angle_density(p_uv, m) * placement_jacobian(s.wi);
  } else if (has_normal(q)) {
    const Frame frame(normalize(q.n));
    s.wi = normalize(frame.to_world(sample_uniform_hemisphere(u)));
    s.pdf = uniform_hemisphere_pdf();
  } else {
    s.wi = sample_uniform_sphere(u);
    s.pdf = uniform_sphere_pdf();
  }
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return std::nullopt;
  s.li = radiance(s.wi);
  s.distance = kTargetDistanceRadii * scene_radius_;
  s.p_light = q.p + s.wi * s.distance;
  return s;
}

float ImageInfiniteLight::pdf_direction(const LightQuery& q, Vec3f wi) const {
  if (sampling_ == EnvMapSampling::ImportanceSampled) return importance_pdf(wi);
  if (!has_normal(q)) return uniform_sphere_pdf();
  return dot(q.n, wi) > 0.0f ? uniform_hemisphere_pdf() : 0.0f;
}

float ImageInfiniteLight::pdf_li(const LightQuery& q, Vec3f p_light, Vec3f, uint32_t) const {
  const Vec3f d = p_light - q.p;
  const float len = length(d);
  return len > 0.0f ? pdf_direction(q, d / len) : 0.0f;
}

// pbrt's estimate for infinite lights: the flux through the scene's disk, pi r^2 times the integral of L.
float ImageInfiniteLight::power() const { return float(kPi * scene_radius_ * scene_radius_ * radiant_integral_); }

}  // namespace kiln
