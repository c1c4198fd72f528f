#include "media/cloud_medium.h"

#include <algorithm>

#include "core/perlin.h"
#include "media/describe_util.h"

namespace kiln {
namespace {

// The wisps: octaves of the noise's gradient that displace the lookup point.
constexpr int kWispOctaves = 2;
constexpr float kWispAmplitude = 0.05f;  // per unit of wispiness
constexpr float kWispFrequency = 10.0f;
// The body: octaves of noise, halving in amplitude.
constexpr int kBodyOctaves = 5;
constexpr float kBodyAmplitude = 0.5f;
// Height profile: the noise's gain grows as (1 - y) times this (times "density"); below kBaseHeight the base term
// 2 (kBaseHeight - y) adds to it, and reaches 1 (a solid cloud) at y = 0.
constexpr float kHeightGain = 4.5f;
constexpr float kBaseHeight = 0.5f;
constexpr float kBaseSlope = 2.0f;

bool inside(const Bounds3f& b, Vec3f p) {
  return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z && p.z <= b.hi.z;
}

Vec3f wisp_displaced(Vec3f q, float wispiness) {
  float amplitude = kWispAmplitude * wispiness, frequency = kWispFrequency;
  for (int i = 0; i < kWispOctaves; ++i) {
    q += course_perlin_gradient(q * frequency) * amplitude;
    amplitude *= 0.5f;
    frequency *= kOctaveLacunarity;
  }
  return q;
}

float body_noise(Vec3f q) {
  float sum = 0.0f, amplitude = kBodyAmplitude, frequency = 1.0f;
  for (int i = 0; i < kBodyOctaves; ++i) {
    sum += amplitude * course_perlin(q * frequency);
    amplitude *= 0.5f;
    frequency *= kOctaveLacunarity;
  }
  return sum;
}

}  // namespace

CloudMedium::CloudMedium(const Transform& medium_to_world, const Bounds3f& bounds, Rgb sigma_a, Rgb sigma_s,
                         float g, CloudShape shape)
    : box_(medium_to_world, bounds),
      world_to_medium_(medium_to_world.inverse()),
      sigma_a_(sigma_a),
      sigma_s_(sigma_s),
      phase_{g},
      shape_(shape) {}

float CloudMedium::density(Vec3f p) const {
  if (!inside(box_.bounds(), p)) return 0.0f;
  Vec3f q = p * shape_.frequency;
  if (shape_.wispiness > 0.0f) q = wisp_displaced(q, shape_.wispiness);
  const float body = std::clamp(kHeightGain * shape_.density * (1.0f - p.y) * body_noise(q), 0.0f, 1.0f);
  const float base = kBaseSlope * std::max(0.0f, kBaseHeight - p.y);
  return std::clamp(body + base, 0.0f, 1.0f);
}

MediumProperties CloudMedium::at(Vec3f p) const {
  const float d = density(world_to_medium_.point(p));
  return {sigma_a_ * d, sigma_s_ * d, Rgb(0.0f)};
}

CloudMedium::Majorants CloudMedium::majorants(const Ray& ray, float tmax) const {
  Vec3f o, d;
  float t0, t1;
  if (!box_.clip(ray, tmax, o, d, t0, t1)) return {};
  return SingleMajorant(MajorantSegment{t0, t1, sigma_a_ + sigma_s_});
}

std::string CloudMedium::describe() const {
  return "cloud density " + describe_float(shape_.density) + " wispiness " + describe_float(shape_.wispiness) +
         " frequency " + describe_float(shape_.frequency) + " sigma_a " + describe_rgb(sigma_a_) + " sigma_s " +
         describe_rgb(sigma_s_) + " g " + describe_float(phase_.g) +
         " (Kiln's noise permutation: pbrt-v4's kind of cloud, not its exact pattern)";
}

}  // namespace kiln
