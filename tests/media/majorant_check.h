// Whether a medium's majorant segments bound its extinction along rays: points spread evenly over every segment, the
// worst channel's excess of sigma_t over sigma_maj (relative, so 0 when every point is bounded).
#pragma once
#include <algorithm>

#include "media/medium.h"

namespace kiln::test {

struct MajorantCheck {
  int points = 0;
  float worst_excess = 0.0f;  // max over points and channels of sigma_t / sigma_maj - 1, clamped below at 0
  Vec3f worst_at;
};

template <typename M>
void check_majorants(const M& m, const Ray& ray, float tmax, int per_segment, MajorantCheck& out) {
  auto segs = m.majorants(ray, tmax);
  MajorantSegment s;
  while (segs.next(s))
    for (int k = 0; k < per_segment; ++k) {
      const Vec3f p = ray.at(s.t0 + (s.t1 - s.t0) * (float(k) + 0.5f) / float(per_segment));
      const MediumProperties mp = m.at(p);
      ++out.points;
      for (int c = 0; c < 3; ++c) {
        const float st = mp.sigma_a[c] + mp.sigma_s[c];
        // Float rounding of the interpolation: a relative slack of 1e-5.
        const float excess = st <= s.sigma_maj[c] * (1.0f + 1e-5f) ? 0.0f : (s.sigma_maj[c] > 0 ? st / s.sigma_maj[c] - 1.0f : 1.0f);
        if (excess > out.worst_excess) out.worst_excess = excess, out.worst_at = p;
      }
    }
}

}  // namespace kiln::test
