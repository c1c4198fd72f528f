// Tentative collisions along a ray through a medium, sampled against its majorants (pbrt-v4's SampleT_maj, the
// common core of delta tracking and ratio tracking). In each majorant segment, distances between collisions are
// drawn from the exponential distribution of one channel's majorant (the path's hero channel, see
// renderer/integrators/vol_path_tracer.cpp); at each collision `collision(p, props, sigma_maj, T_maj)` is called
// with the medium there and the majorant transmittance of every channel since the previous collision, and returns
// whether the walk goes on. What the caller does there (absorb, scatter, null-collide; or multiply a ratio) makes
// the estimator.
#pragma once
#include <cmath>
#include <cstdint>
#include <variant>

#include "core/rng.h"
#include "media/medium.h"

namespace kiln {

// Per-thread tracking statistics (kiln render --stats, kiln profile): steps per ray and majorant efficiency.
struct TrackingCounters {
  uint64_t rays = 0;           // ray segments tracked through a medium
  uint64_t collisions = 0;     // tentative collisions (tracking steps)
  double extinction_ratio = 0;  // sum over collisions of sigma_t / sigma_maj of the tracked channel
  void add(const TrackingCounters& o) {
    rays += o.rays;
    collisions += o.collisions;
    extinction_ratio += o.extinction_ratio;
  }
  double steps_per_ray() const { return rays ? double(collisions) / double(rays) : 0.0; }
  // The mean of sigma_t / sigma_maj at the collisions: 1 when every collision is real (a homogeneous medium), low
  // when majorants are loose and tracking wastes steps on null collisions.
  double majorant_efficiency() const { return collisions ? extinction_ratio / double(collisions) : 0.0; }
};

// exp(-sigma * dt) per channel, with an infinite dt through a channel of zero extinction giving 1 (not NaN).
inline Rgb majorant_transmittance(Rgb sigma, float dt) {
  Rgb t;
  for (int c = 0; c < 3; ++c) t[c] = sigma[c] == 0.0f ? 1.0f : std::exp(-sigma[c] * dt);
  return t;
}

// A distance with density a exp(-a t).
inline float sample_exponential(float u, float a) { return -std::log1p(-u) / a; }

// ray: unit direction; tmax: where the medium ends along it (a surface, or infinity); u: the first distance's
// uniform sample (stratified by the caller), later ones come from rng. Returns the majorant transmittance from the
// last collision to tmax, or Rgb(1) when `collision` ended the walk.
template <typename M, typename Collision>
Rgb sample_collisions(const M& medium, const Ray& ray, float tmax, float u, Rng& rng, int channel,
                      Collision&& collision) {
  typename M::Majorants segments = medium.majorants(ray, tmax);
  Rgb t_maj(1.0f);
  MajorantSegment seg;
  while (segments.next(seg)) {
    const float sigma = seg.sigma_maj[channel];
    if (sigma == 0.0f) {
      t_maj *= majorant_transmittance(seg.sigma_maj, seg.t1 - seg.t0);
      continue;
    }
    for (float t = seg.t0;;) {
      const float step = sample_exponential(u, sigma);
      u = rng.next_float();
      if (!(t + step < seg.t1)) {
        t_maj *= majorant_transmittance(seg.sigma_maj, seg.t1 - t);
        break;
      }
      t += step;
      t_maj *= majorant_transmittance(seg.sigma_maj, step);
      const Vec3f p = ray.at(t);
      if (!collision(p, medium.at(p), seg.sigma_maj, t_maj)) return Rgb(1.0f);
      t_maj = Rgb(1.0f);
    }
  }
  return t_maj;
}

template <typename Collision>
Rgb sample_collisions(const Medium& medium, const Ray& ray, float tmax, float u, Rng& rng, int channel,
                      Collision&& collision) {
  return std::visit([&](const auto& m) { return sample_collisions(m, ray, tmax, u, rng, channel, collision); }, medium);
}

}  // namespace kiln
