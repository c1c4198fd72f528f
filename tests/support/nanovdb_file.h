// Writes NanoVDB files for tests, through Debian's NanoVDB (GridBuilder + io::writeGrid): a dense lattice becomes a
// float fog-volume grid whose voxel (x, y, z) holds v[x + nx (y + ny z)] at world position origin + voxel * (x, y, z).
#pragma once
#include <string>
#include <vector>

#define NANOVDB_USE_ZIP 1
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>

namespace kiln::test {

struct NanoVdbLattice {
  std::vector<float> values;
  int nx = 0, ny = 0, nz = 0;
  double origin[3] = {0, 0, 0};
  double voxel = 1.0;
  std::string name = "density";
};

inline nanovdb::GridHandle<> nanovdb_grid(const NanoVdbLattice& l) {
  nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
  auto acc = builder.getAccessor();
  for (int z = 0; z < l.nz; ++z)
    for (int y = 0; y < l.ny; ++y)
      for (int x = 0; x < l.nx; ++x)
        acc.setValue(nanovdb::Coord(x, y, z), l.values[(size_t(z) * size_t(l.ny) + size_t(y)) * size_t(l.nx) + size_t(x)]);
  return builder.getHandle<>(l.voxel, nanovdb::Vec3d(l.origin[0], l.origin[1], l.origin[2]), l.name);
}

// Several grids in one file (e.g. density and temperature).
inline void write_nanovdb(const std::string& path, const std::vector<NanoVdbLattice>& grids,
                          nanovdb::io::Codec codec = nanovdb::io::Codec::NONE) {
  std::vector<nanovdb::GridHandle<>> handles;
  for (const NanoVdbLattice& l : grids) handles.push_back(nanovdb_grid(l));
  nanovdb::io::writeGrids(path, handles, codec);
}

}  // namespace kiln::test
