#include "lights/image_infinite_light.h"

#include <algorithm>
#include <cmath>

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

ImageInfiniteLight::ImageInfiniteLight(Image image, float scene_radius, EnvMapSampling sampling)
    : image_(std::move(image)), scene_radius_(scene_radius), sampling_(sampling) {
  if (image_.width() <= 0 || image_.height() <= 0) throw Error("environment map: the image is empty");
  if (!(scene_radius > 0.0f) || !std::isfinite(scene_radius))
    throw Error("environment light: the scene radius must be positive");
  for (Rgb& c : image_.pixels()) c = usable(c);
  const int w = image_.width(), h = image_.height();
  std::vector<float> row_weights(static_cast<size_t>(h)), texel(static_cast<size_t>(w));
  columns_.reserve(size_t(h));
  for (int y = 0; y < h; ++y) {
    const float sin_theta = std::sin(kPi * (float(y) + 0.5f) / float(h));
    double row = 0.0, row_luminance = 0.0;
    for (int x = 0; x < w; ++x) {
      texel[size_t(x)] = image_.at(x, y).luminance() * sin_theta;
      row += texel[size_t(x)];
      row_luminance += image_.at(x, y).luminance();
    }
    columns_.emplace_back(texel);
    row_weights[size_t(y)] = float(row);
    // A texel of this row spans the solid angle (2 pi / w) (cos theta_top - cos theta_bottom).
    const double band = std::cos(kPi * double(y) / h) - std::cos(kPi * double(y + 1) / h);
    radiant_integral_ += row_luminance * (2.0 * kPi / w) * band;
  }
  rows_ = Distribution1D(row_weights);
}

int ImageInfiniteLight::texel_x(float u) const { return std::clamp(int(u * float(image_.width())), 0, image_.width() - 1); }
int ImageInfiniteLight::texel_y(float v) const {
  return std::clamp(int(v * float(image_.height())), 0, image_.height() - 1);
}

Rgb ImageInfiniteLight::radiance(Vec3f d) const {
  const Vec2f uv = lat_long(d);
  return image_.at(texel_x(uv.x), texel_y(uv.y));
}

float ImageInfiniteLight::importance_pdf(Vec3f wi) const {
  const Vec2f uv = lat_long(wi);
  const int x = texel_x(uv.x), y = texel_y(uv.y);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - wi.y * wi.y));
  if (!(sin_theta > 0.0f)) return 0.0f;
  const float p_uv = rows_.pmf(size_t(y)) * columns_[size_t(y)].pmf(size_t(x)) * float(image_.width()) *
                     float(image_.height());
  return p_uv / (2.0f * kPi * kPi * sin_theta);
}

std::optional<LightSample> ImageInfiniteLight::sample_li(const LightQuery& q, Vec2f u) const {
  LightSample s;
  if (sampling_ == EnvMapSampling::ImportanceSampled) {
    float row_pmf = 0.0f, column_pmf = 0.0f, v_in = 0.0f, u_in = 0.0f;
    const size_t y = rows_.sample(u.y, &row_pmf, &v_in);
    if (!(row_pmf > 0.0f)) return std::nullopt;
    const size_t x = columns_[y].sample(u.x, &column_pmf, &u_in);
    if (!(column_pmf > 0.0f)) return std::nullopt;
    const float uu = (float(x) + u_in) / float(image_.width()), vv = (float(y) + v_in) / float(image_.height());
    s.wi = direction(uu, vv);
    // The chosen texel's density: what pdf_direction gives wi (it maps wi back to the same texel, except within
    // float rounding of a texel edge).
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - s.wi.y * s.wi.y));
    if (!(sin_theta > 0.0f)) return std::nullopt;
    s.pdf = row_pmf * column_pmf * float(image_.width()) * float(image_.height()) / (2.0f * kPi * kPi * sin_theta);
  } else if (has_normal(q)) {
    const Frame frame(normalize(q.n));
    s.wi = normalize(frame.to_world(sample_uniform_hemisphere(u)));
    s.pdf = uniform_hemisphere_pdf();
  } else {
    s.wi = sample_uniform_sphere(u);
    s.pdf = uniform_sphere_pdf();
  }
  if (!(s.pdf > 0.0f)) return std::nullopt;
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
