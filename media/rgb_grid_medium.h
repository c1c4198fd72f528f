// pbrt-v4's "rgbgrid" medium: per-sample RGB coefficients over the box [p0, p1] of the medium's space.
//
// Parameters (scenes/pbrt/media.cpp):
//   sigma_a, sigma_s   nx x ny x nz RGB lattices (either may be absent: then 1 everywhere), times "scale"
//   le                 an RGB lattice of emitted radiance (needs sigma_a), times "Lescale"
//   g                  Henyey-Greenstein asymmetry
// The majorant grid bounds the largest channel of sigma_a + sigma_s in each voxel (one value for all channels, as
// pbrt-v4 does).
#pragma once
#include <optional>
#include <string>

#include "materials/henyey_greenstein.h"
#include "media/majorant_grid.h"
#include "media/medium_properties.h"
#include "media/sampled_grid.h"

namespace kiln {

class RgbGridMedium {
 public:
  using Majorants = DdaMajorantIterator;

  // Absent lattices are empty grids. scale multiplies sigma_a and sigma_s, le_scale the emission.
  RgbGridMedium(const Transform& medium_to_world, const Bounds3f& bounds, SampledGrid<Rgb> sigma_a,
                SampledGrid<Rgb> sigma_s, float scale, SampledGrid<Rgb> le, float le_scale, float g);

  MediumProperties at(Vec3f p) const;
  Majorants majorants(const Ray& ray, float tmax) const;
  const HenyeyGreenstein& phase() const { return phase_; }
  bool emissive() const { return !le_.empty() && le_scale_ > 0.0f; }
  const MajorantGrid& majorant_grid() const { return majorant_; }
  std::string describe() const;

 private:
  MediumBox box_;
  SampledGrid<Rgb> sigma_a_, sigma_s_, le_;
  float scale_ = 1.0f, le_scale_ = 1.0f;
  HenyeyGreenstein phase_;
  MajorantGrid majorant_;
};

}  // namespace kiln
