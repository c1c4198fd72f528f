#include "lights/infinite_light.h"

#include "core/error.h"
#include "core/frame.h"
#include "core/sampling.h"

namespace kiln {
namespace {

// Shadow-ray targets sit this many scene radii from the query point (outside every object).
constexpr float kTargetDistanceRadii = 2.0f;

bool has_normal(const LightQuery& q) { return length_squared(q.n) > 0.0f; }

}  // namespace

InfiniteLight::InfiniteLight(Rgb radiance, float scene_radius) : radiance_(radiance), scene_radius_(scene_radius) {
  if (!radiance.is_finite() || radiance.has_negative())
    throw Error("infinite light: radiance must be finite and non-negative");
  if (!(scene_radius > 0.0f) || !std::isfinite(scene_radius))
    throw Error("infinite light: the scene radius must be positive");
}

std::optional<LightSample> InfiniteLight::sample_li(const LightQuery& q, Vec2f u) const {
  LightSample s;
  if (has_normal(q)) {
    const Frame frame(normalize(q.n));
    const Vec3f local = sample_cosine_hemisphere(u);
    s.wi = normalize(frame.to_world(local));
    s.pdf = cosine_hemisphere_pdf(local.z);
  } else {
    s.wi = sample_uniform_sphere(u);
    s.pdf = uniform_sphere_pdf();
  }
  if (!(s.pdf > 0.0f)) return std::nullopt;
  s.li = radiance_;
  s.distance = kTargetDistanceRadii * scene_radius_;
  s.p_light = q.p + s.wi * s.distance;
  return s;
}

float InfiniteLight::pdf_direction(const LightQuery& q, Vec3f wi) const {
  if (!has_normal(q)) return uniform_sphere_pdf();
  return cosine_hemisphere_pdf(dot(normalize(q.n), wi));
}

float InfiniteLight::pdf_li(const LightQuery& q, Vec3f p_light, Vec3f, uint32_t) const {
  const Vec3f d = p_light - q.p;
  const float len = length(d);
  return len > 0.0f ? pdf_direction(q, d / len) : 0.0f;
}

float InfiniteLight::power() const { return 4.0f * kPi * kPi * scene_radius_ * scene_radius_ * radiance_.luminance(); }

}  // namespace kiln
