// A dense lattice of samples over the unit cube, read by trilinear interpolation (pbrt-v4's SampledGrid
// definition): sample (x, y, z) of an nx x ny x nz grid sits at ((x + 1/2) / nx, (y + 1/2) / ny, (z + 1/2) / nz),
// stored x fastest, and samples outside the lattice are zero. So a grid's values fade to zero over the half voxel
// next to the unit cube's faces, as pbrt renders them.
#pragma once
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/bounds.h"

namespace kiln {

template <typename T>
class SampledGrid {
 public:
  SampledGrid() = default;
  // values.size() must be nx * ny * nz (the caller checks it; scenes/pbrt/media.cpp reports a mismatch).
  SampledGrid(std::vector<T> values, int nx, int ny, int nz) : values_(std::move(values)), n_{nx, ny, nz} {}

  bool empty() const { return values_.empty(); }
  int size(int axis) const { return n_[axis]; }
  size_t bytes() const { return values_.size() * sizeof(T); }

  // Sample (x, y, z), zero outside the lattice.
  T sample(int x, int y, int z) const {
    if (x < 0 || y < 0 || z < 0 || x >= n_[0] || y >= n_[1] || z >= n_[2]) return T{};
    return values_[(size_t(z) * size_t(n_[1]) + size_t(y)) * size_t(n_[0]) + size_t(x)];
  }

  // Trilinear interpolation at p in the unit cube's coordinates.
  T lookup(Vec3f p) const {
    float f[3];
    int i[3];
    for (int a = 0; a < 3; ++a) {
      const float s = p[a] * float(n_[a]) - 0.5f;
      if (!(s >= -1.0f && s < float(n_[a]))) return T{};  // beyond the last samples (or NaN): nothing to blend
      const float fl = std::floor(s);
      i[a] = int(fl);
      f[a] = s - fl;
    }
    const auto lerp_x = [&](int y, int z) {
      return sample(i[0], y, z) * (1.0f - f[0]) + sample(i[0] + 1, y, z) * f[0];
    };
    const T y0 = lerp_x(i[1], i[2]) * (1.0f - f[1]) + lerp_x(i[1] + 1, i[2]) * f[1];
    const T y1 = lerp_x(i[1], i[2] + 1) * (1.0f - f[1]) + lerp_x(i[1] + 1, i[2] + 1) * f[1];
    return y0 * (1.0f - f[2]) + y1 * f[2];
  }

  // The largest of value_of(sample) over the samples that interpolation reads anywhere in `region` (unit-cube
  // coordinates): a bound on value_of(lookup(p)) there when value_of is convex-monotone (a maximum or a sum of
  // non-negative parts, as majorants use it).
  template <typename F>
  float max_over(const Bounds3f& region, F&& value_of) const {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(0, int(std::floor(region.lo[a] * float(n_[a]) - 0.5f)));
      hi[a] = std::min(n_[a] - 1, int(std::floor(region.hi[a] * float(n_[a]) - 0.5f)) + 1);
    }
    float m = 0.0f;
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) m = std::max(m, value_of(sample(x, y, z)));
    return m;
  }

 private:
  std::vector<T> values_;
  int n_[3] = {0, 0, 0};
};

}  // namespace kiln
