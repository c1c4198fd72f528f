// pbrt-v4's "uniformgrid" medium: a density lattice over the box [p0, p1] of the medium's space, scaling constant
// coefficients: sigma_a(p) = d(p) sigma_a, sigma_s(p) = d(p) sigma_s, with d read by trilinear interpolation
// (media/sampled_grid.h: zero outside the lattice, so the density fades over the half voxel inside the faces).
//
// Parameters (scenes/pbrt/media.cpp):
//   density             nx x ny x nz non-negative values, x fastest
//   sigma_a, sigma_s    per unit length at density 1 (times "scale")
//   g                   Henyey-Greenstein asymmetry
//   emission            an "Lescale" lattice (a single value when absent, which pbrt-v4 reads as a 1x1x1 lattice,
//                       so it too fades towards the faces) times either a constant radiance le or the blackbody
//                       radiance of a "temperature" lattice at (T - offset) * scale (emission_table.h)
// The majorant grid holds the largest density each of its voxels can interpolate (16^3 at most, as pbrt-v4).
#pragma once
#include <string>
#include <vector>

#include "materials/henyey_greenstein.h"
#include "media/majorant_grid.h"
#include "media/medium_properties.h"
#include "media/sampled_grid.h"

namespace kiln {

struct GridEmission {
  Rgb le{0.0f};
  SampledGrid<float> le_scale;        // required with le or temperature
  SampledGrid<float> temperature;     // empty: emission is le * le_scale
  float temperature_offset = 0.0f, temperature_scale = 1.0f;
  std::vector<Rgb> blackbody;         // emission_table.h; read only with a temperature lattice
  bool any() const { return !temperature.empty() || !le.is_black(); }
};

class GridMedium {
 public:
  using Majorants = DdaMajorantIterator;

  GridMedium(const Transform& medium_to_world, const Bounds3f& bounds, Rgb sigma_a, Rgb sigma_s, float g,
             SampledGrid<float> density, GridEmission emission);

  MediumProperties at(Vec3f p) const;
  Majorants majorants(const Ray& ray, float tmax) const;
  const HenyeyGreenstein& phase() const { return phase_; }
  bool emissive() const { return emission_.any() && !sigma_a_.is_black(); }
  const MajorantGrid& majorant_grid() const { return majorant_; }
  std::string describe() const;

 private:
  MediumBox box_;
  Rgb sigma_a_, sigma_s_;
  HenyeyGreenstein phase_;
  SampledGrid<float> density_;
  GridEmission emission_;
  MajorantGrid majorant_;
};

}  // namespace kiln
