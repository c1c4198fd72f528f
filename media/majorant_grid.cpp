#include "media/majorant_grid.h"

#include <algorithm>
#include <cmath>

namespace kiln {

MediumBox::MediumBox(const Transform& medium_to_world, const Bounds3f& bounds) : bounds_(bounds) {
  const Vec3f ext = bounds.diagonal();
  const Vec3f inv(1.0f / ext.x, 1.0f / ext.y, 1.0f / ext.z);
  world_to_unit_ = Transform::scale(inv) * Transform::translate(-bounds.lo) * medium_to_world.inverse();
}

bool MediumBox::clip(const Ray& ray, float tmax, Vec3f& o_unit, Vec3f& d_unit, float& t0, float& t1) const {
  o_unit = world_to_unit_.point(ray.o);
  d_unit = world_to_unit_.vector(ray.d);
  t0 = 0.0f;
  t1 = tmax;
  for (int a = 0; a < 3; ++a) {  // the slabs between the planes 0 and 1 of each axis
    if (d_unit[a] == 0.0f) {       // parallel to them: inside for every t, or never
      if (!(o_unit[a] >= 0.0f && o_unit[a] <= 1.0f)) return false;
      continue;
    }
    const float inv = 1.0f / d_unit[a];
    float near = -o_unit[a] * inv, far = (1.0f - o_unit[a]) * inv;
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1) return false;
  }
  return t0 < t1;
}

DdaMajorantIterator MediumBox::majorants(const MajorantGrid& grid, const Ray& ray, float tmax, Rgb sigma_t) const {
  Vec3f o, d;
  float t0, t1;
  if (!clip(ray, tmax, o, d, t0, t1)) return {};
  return DdaMajorantIterator(grid, o, d, t0, t1, sigma_t);
}

MajorantGrid::MajorantGrid(int rx, int ry, int rz) : v_(size_t(rx) * size_t(ry) * size_t(rz), 0.0f), res_{rx, ry, rz} {}

std::string MajorantGrid::describe() const {
  return std::to_string(res_[0]) + "x" + std::to_string(res_[1]) + "x" + std::to_string(res_[2]);
}

Bounds3f MajorantGrid::voxel_region(int x, int y, int z) const {
  const Vec3f lo(float(x) / float(res_[0]), float(y) / float(res_[1]), float(z) / float(res_[2]));
  const Vec3f hi(float(x + 1) / float(res_[0]), float(y + 1) / float(res_[1]), float(z + 1) / float(res_[2]));
  return Bounds3f(lo, hi);
}

DdaMajorantIterator::DdaMajorantIterator(const MajorantGrid& grid, Vec3f o, Vec3f d, float t0, float t1,
                                         Rgb sigma_t)
    : grid_(&grid), sigma_t_(sigma_t), t_(t0), t_end_(t1) {
  const Vec3f p = o + d * t0;
  for (int a = 0; a < 3; ++a) {
    const int res = grid.res(a);
    voxel_[a] = std::clamp(int(p[a] * float(res)), 0, res - 1);
    if (d[a] == 0.0f) {  // never crosses a plane of this axis
      next_crossing_[a] = kInfinity;
      delta_[a] = kInfinity;
      step_[a] = 1;
      limit_[a] = res;
      continue;
    }
    delta_[a] = 1.0f / (std::abs(d[a]) * float(res));
    const bool up = d[a] > 0.0f;
    const float plane = float(voxel_[a] + (up ? 1 : 0)) / float(res);
    next_crossing_[a] = t0 + (plane - p[a]) / d[a];
    step_[a] = up ? 1 : -1;
    limit_[a] = up ? res : -1;
  }
}

bool DdaMajorantIterator::next(MajorantSegment& seg) {
  if (!grid_ || !(t_ < t_end_)) return false;
  int axis = 0;
  if (next_crossing_[1] < next_crossing_[axis]) axis = 1;
  if (next_crossing_[2] < next_crossing_[axis]) axis = 2;
  const float exit = std::min(t_end_, next_crossing_[axis]);
  seg = MajorantSegment{t_, exit, sigma_t_ * grid_->at(voxel_[0], voxel_[1], voxel_[2])};
  t_ = exit;
  voxel_[axis] += step_[axis];
  // Past the last voxel or the segment's end: this was the last segment.
  if (next_crossing_[axis] >= t_end_ || voxel_[axis] == limit_[axis]) t_ = t_end_;
  next_crossing_[axis] += delta_[axis];
  return true;
}

}  // namespace kiln
