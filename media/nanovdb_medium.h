// pbrt-v4's "nanovdb" medium: density (and optionally temperature) from a NanoVDB file (.nvdb, read with Debian's
// libnanovdb-dev), in the medium's space as the file's own grid transform places it.
//
// Parameters (scenes/pbrt/media.cpp):
//   path                 the .nvdb file (a float grid named density_grid, a FogVolume or of unknown class; its
//                        temperature_grid is optional); uncompressed or ZIP-compressed
//   sigma_a, sigma_s     per unit length at density 1 (times "scale")
//   g                    Henyey-Greenstein asymmetry
//   le_scale, temperature_offset, temperature_scale, blackbody
//                        emission: le_scale * blackbody((T - offset) * scale) (emission_table.h)
// Densities are read by trilinear interpolation of the voxel values (NanoVDB's SampleFromVoxels, order 1), like
// pbrt-v4. The box is the grid's world bounding box; the majorant grid (up to 64^3, as pbrt-v4) is built from the
// tree's own nodes: each leaf's largest value (active or not: interpolation reads both) and each constant tile,
// spread over the cells their values can be interpolated into.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "materials/henyey_greenstein.h"
#include "media/majorant_grid.h"
#include "media/medium_properties.h"

namespace kiln {

inline constexpr int kNanoVdbMajorantResolution = 64;

struct NanoVdbParams {
  std::string path;
  std::string density_grid = "density", temperature_grid = "temperature";
  Rgb sigma_a{1.0f}, sigma_s{1.0f};
  float g = 0.0f;
  float le_scale = 1.0f, temperature_offset = 0.0f, temperature_scale = 1.0f;
  std::vector<Rgb> blackbody;  // emission_table.h
};

struct NanoVdbGrids;  // the file's grids in NanoVDB's types (nanovdb_medium.cpp)

class NanoVdbMedium {
 public:
  using Majorants = DdaMajorantIterator;

  // Reads the file; throws kiln::Error naming it and what is wrong (missing, not NanoVDB, no such float grid,
  // corrupt).
  NanoVdbMedium(const NanoVdbParams& params, const Transform& medium_to_world);

  MediumProperties at(Vec3f p) const;
  Majorants majorants(const Ray& ray, float tmax) const;
  const HenyeyGreenstein& phase() const { return phase_; }
  bool emissive() const;
  const MajorantGrid& majorant_grid() const { return majorant_; }
  uint64_t active_voxels() const;
  size_t grid_bytes() const;
  std::string describe() const;

 private:
  std::shared_ptr<const NanoVdbGrids> grids_;  // shared: a World's media are copied, never the grids
  Transform world_to_medium_;
  MediumBox box_;
  Rgb sigma_a_, sigma_s_;
  HenyeyGreenstein phase_;
  float le_scale_, temperature_offset_, temperature_scale_;
  std::vector<Rgb> blackbody_;
  MajorantGrid majorant_;
};

}  // namespace kiln
