// Majorants: upper bounds on a medium's extinction along a ray, against which delta and ratio tracking sample
// tentative collisions (media/tracking.h). A homogeneous medium is its own majorant (one segment); a heterogeneous
// one keeps a coarse grid of maximum densities over its box (pbrt-v4's MajorantGrid), walked voxel by voxel with a
// 3-D DDA, so a dense but sparse cloud is tracked against the local maximum rather than the global one.
#pragma once
#include <string>
#include <vector>

#include "core/bounds.h"
#include "core/color.h"
#include "core/ray.h"
#include "core/transform.h"

namespace kiln {

// sigma_maj bounds sigma_t on [t0, t1) of the ray (t in the ray's units: distance along a unit direction).
struct MajorantSegment {
  float t0 = 0.0f, t1 = 0.0f;
  Rgb sigma_maj;
};

// One segment: homogeneous media (the whole ray), the cloud (the ray's part inside its box).
class SingleMajorant {
 public:
  SingleMajorant() = default;  // a ray that misses the medium: no segment
  explicit SingleMajorant(MajorantSegment s) : seg_(s), done_(false) {}
  bool next(MajorantSegment& s) {
    if (done_) return false;
    s = seg_;
    done_ = true;
    return true;
  }

 private:
  MajorantSegment seg_;
  bool done_ = true;
};

class MajorantGrid {
 public:
  MajorantGrid() = default;
  MajorantGrid(int rx, int ry, int rz);
  // Sets every voxel to max_over(region), region being the voxel in unit-cube coordinates.
  template <typename MaxOver>
  void fill(MaxOver&& max_over) {
    for (int z = 0; z < res_[2]; ++z)
      for (int y = 0; y < res_[1]; ++y)
        for (int x = 0; x < res_[0]; ++x) v_[index(x, y, z)] = max_over(voxel_region(x, y, z));
  }
  void set(int x, int y, int z, float v) { v_[index(x, y, z)] = v; }
  float at(int x, int y, int z) const { return v_[index(x, y, z)]; }
  int res(int axis) const { return res_[axis]; }
  size_t voxels() const { return v_.size(); }
  std::string describe() const;  // "16x16x8"
  Bounds3f voxel_region(int x, int y, int z) const;

 private:
  size_t index(int x, int y, int z) const { return (size_t(z) * size_t(res_[1]) + size_t(y)) * size_t(res_[0]) + size_t(x); }
  std::vector<float> v_;
  int res_[3] = {0, 0, 0};
};

// The majorant voxels a ray crosses, in order (Amanatides-Woo 3-D DDA), one segment each with
// sigma_maj = sigma_t * the voxel's maximum density.
class DdaMajorantIterator {
 public:
  DdaMajorantIterator() = default;  // a ray that misses the box: no segments
  // o, d: the ray in unit-cube coordinates; [t0, t1): its part inside the cube (MediumBox::clip).
  DdaMajorantIterator(const MajorantGrid& grid, Vec3f o, Vec3f d, float t0, float t1, Rgb sigma_t);
  bool next(MajorantSegment& seg);

 private:
  const MajorantGrid* grid_ = nullptr;
  Rgb sigma_t_;
  float t_ = 0.0f, t_end_ = 0.0f;
  float next_crossing_[3] = {}, delta_[3] = {};
  int step_[3] = {}, voxel_[3] = {}, limit_[3] = {};
};

// A heterogeneous medium's box in its own space and the map from world space to the box's unit cube, where its
// grids and its majorant grid live.
class MediumBox {
 public:
  MediumBox() = default;
  MediumBox(const Transform& medium_to_world, const Bounds3f& bounds);
  Vec3f unit_point(Vec3f p_world) const { return world_to_unit_.point(p_world); }
  // The part [t0, t1) of ray (o + t d, t in [0, tmax)) inside the box; false when it misses. o_unit and d_unit
  // describe the ray in unit-cube coordinates with the same parameter t.
  bool clip(const Ray& ray, float tmax, Vec3f& o_unit, Vec3f& d_unit, float& t0, float& t1) const;
  // The majorant segments of the ray's part inside the box (none when it misses): grid's voxels times sigma_t.
  DdaMajorantIterator majorants(const MajorantGrid& grid, const Ray& ray, float tmax, Rgb sigma_t) const;
  const Bounds3f& bounds() const { return bounds_; }

 private:
  Bounds3f bounds_;
  Transform world_to_unit_;
};

// Majorant grid resolution of the lattice media (uniformgrid, rgbgrid), as pbrt-v4's.
inline constexpr int kGridMajorantResolution = 16;

// The majorant grid resolution along an axis holding n samples: a voxel should cover a few samples, and never
// fewer than one.
inline int majorant_resolution(int n, int max_res) { return n < 1 ? 1 : (n < max_res ? n : max_res); }

}  // namespace kiln
