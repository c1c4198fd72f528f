#include "media/nanovdb_medium.h"

#include <algorithm>
#include <cstring>
#include <fstream>

#include <iostream>  // nanovdb/util/GridValidator.h uses std::cerr without including it

#define NANOVDB_USE_ZIP 1
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include "core/error.h"
#include "media/describe_util.h"
#include "media/emission_table.h"

namespace kiln {

struct NanoVdbGrids {
  nanovdb::GridHandle<nanovdb::HostBuffer> density_handle, temperature_handle;
  const nanovdb::FloatGrid* density = nullptr;
  const nanovdb::FloatGrid* temperature = nullptr;  // optional
};

namespace {

using FloatTree = nanovdb::FloatGrid::TreeType;

// Trilinear interpolation of the voxel values around p (the grid's world space, Kiln's medium space).
float sample_grid(const nanovdb::FloatGrid& grid, Vec3f p) {
  const nanovdb::Vec3f index = grid.worldToIndexF(nanovdb::Vec3f(p.x, p.y, p.z));
  return nanovdb::SampleFromVoxels<FloatTree, 1, false>(grid.tree())(index);
}

// A NanoVDB file starts with a header: its magic number, then the version that wrote it. Checking the magic number
// first turns "some other file" into a clear message instead of NanoVDB's reading of garbage. A version that is not
// the library's is refused here too, before NanoVDB's reader sees it: the reader's own message for that case leaks
// the version string it formats (nanovdb::Version::c_str mallocs it). A header cut short after the magic number is
// left to the reader, which says so.
void check_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "", "cannot open the NanoVDB file");
  nanovdb::io::Header header;
  in.read(reinterpret_cast<char*>(&header.magic), sizeof header.magic);
  if (!in || header.magic != NANOVDB_MAGIC_NUMBER)
    throw Error(path, "", "is not a NanoVDB file (it does not start with NanoVDB's magic number)");
  if (!in.read(reinterpret_cast<char*>(&header.version), sizeof header.version)) return;
  const nanovdb::Version v = header.version;
  if (v.getMajor() == NANOVDB_MAJOR_VERSION_NUMBER) return;
  throw Error(path, "",
              "written by NanoVDB " + std::to_string(v.getMajor()) + "." + std::to_string(v.getMinor()) + "." +
                  std::to_string(v.getPatch()) + "; Kiln reads files of NanoVDB " +
                  std::to_string(NANOVDB_MAJOR_VERSION_NUMBER) + ".x (rewrite the file with that version)");
}

// NanoVDB's messages span several lines (a diagnosis, then a tab-indented recommendation): one line for Kiln's.
std::string one_line(const std::string& message) {
  std::string out;
  for (const char c : message) {
    const bool space = c == '\n' || c == '\t' || c == ' ';
    if (space && (out.empty() || out.back() == ' ')) continue;
    out.push_back(space ? ' ' : c);
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// The float grid `name` of the file; an empty handle when the file has no grid of that name.
nanovdb::GridHandle<nanovdb::HostBuffer> read_float_grid(const std::string& path, const std::string& name) {
  nanovdb::GridHandle<nanovdb::HostBuffer> handle;
  try {
    handle = nanovdb::io::readGrid<nanovdb::HostBuffer>(path, name);
  } catch (const std::exception& e) {
    throw Error(path, "", "NanoVDB cannot read it: " + one_line(e.what()));
  }
  if (!handle) return handle;
  const nanovdb::FloatGrid* grid = handle.grid<float>();
  if (!grid) throw Error(path, "", "grid " + quoted(name) + " does not hold 32-bit floats");
  if (!grid->isFogVolume() && !grid->isUnknown())
    throw Error(path, "", "grid " + quoted(name) + " is not a fog volume (pbrt-v4 reads densities from those)");
  if (!nanovdb::isValid(*grid, true, false))
    throw Error(path, "", "grid " + quoted(name) + " fails NanoVDB's validation (corrupt or truncated file)");
  return handle;
}

Bounds3f world_bounds(const nanovdb::FloatGrid& g) {
  const auto& b = g.worldBBox();
  return Bounds3f(Vec3f(float(b.min()[0]), float(b.min()[1]), float(b.min()[2])),
                  Vec3f(float(b.max()[0]), float(b.max()[1]), float(b.max()[2])));
}

// Builds the majorant grid of a density grid: every value stored in the tree raises the cells of the region
// where trilinear interpolation can read it (one voxel around the voxels it stands for).
class MajorantBuilder {
 public:
  MajorantBuilder(const nanovdb::FloatGrid& grid, const Bounds3f& box, MajorantGrid& majorant)
      : grid_(grid), box_(box), majorant_(majorant) {}

  void build() {
    const FloatTree& tree = grid_.tree();
    const float floor = std::max(0.0f, tree.background());
    majorant_.fill([&](const Bounds3f&) { return floor; });
    const auto* leaf = tree.getFirstLeaf();
    for (uint32_t i = 0; i < tree.nodeCount(0); ++i) {
      float m = 0.0f;
      for (uint32_t v = 0; v < leaf[i].SIZE; ++v) m = std::max(m, leaf[i].getValue(v));
      raise(leaf[i].origin(), int(leaf[i].DIM), m);
    }
    spread_tiles(tree.getFirstLower(), tree.nodeCount(1));
    spread_tiles(tree.getFirstUpper(), tree.nodeCount(2));
    const auto& root = tree.root();
    for (uint32_t i = 0; i < root.tileCount(); ++i) {
      const auto* tile = root.data()->tile(i);
      if (tile->isValue()) raise(tile->origin(), int(FloatTree::RootType::ChildNodeType::DIM), tile->value);
    }
  }

 private:
  // The constant tiles of internal nodes (slots without a child node).
  template <typename Node>
  void spread_tiles(const Node* nodes, uint32_t count) {
    for (uint32_t i = 0; i < count; ++i)
      for (uint32_t n = 0; n < Node::SIZE; ++n)
        if (!nodes[i].data()->isChild(n))
          raise(nodes[i].offsetToGlobalCoord(n), int(Node::ChildNodeType::DIM), nodes[i].data()->getValue(n));
  }

  // Voxels origin .. origin + size - 1 (index space) hold values up to `value`.
  void raise(const nanovdb::Coord& origin, int size, float value) {
    if (!(value > 0.0f)) return;
    Bounds3f region;
    for (int corner = 0; corner < 8; ++corner) {
      const nanovdb::Vec3f c(static_cast<float>(origin[0]) + ((corner & 1) ? float(size) : -1.0f),
                             static_cast<float>(origin[1]) + ((corner & 2) ? float(size) : -1.0f),
                             static_cast<float>(origin[2]) + ((corner & 4) ? float(size) : -1.0f));
      const nanovdb::Vec3f w = grid_.indexToWorldF(c);
      region.extend(Vec3f(w[0], w[1], w[2]));
    }
    int lo[3], hi[3];
    const Vec3f ext = box_.diagonal();
    for (int a = 0; a < 3; ++a) {
      const float u0 = (region.lo[a] - box_.lo[a]) / ext[a], u1 = (region.hi[a] - box_.lo[a]) / ext[a];
      if (u1 < 0.0f || u0 > 1.0f) return;
      const int res = majorant_.res(a);
      lo[a] = std::clamp(int(std::floor(u0 * float(res))), 0, res - 1);
      hi[a] = std::clamp(int(std::floor(u1 * float(res))), 0, res - 1);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) majorant_.set(x, y, z, std::max(majorant_.at(x, y, z), value));
  }

  const nanovdb::FloatGrid& grid_;
  Bounds3f box_;
  MajorantGrid& majorant_;
};

MajorantGrid majorant_for(const nanovdb::FloatGrid& g) {
  const auto& ib = g.indexBBox();
  const int res[3] = {majorant_resolution(ib.max()[0] - ib.min()[0] + 1, kNanoVdbMajorantResolution),
                      majorant_resolution(ib.max()[1] - ib.min()[1] + 1, kNanoVdbMajorantResolution),
                      majorant_resolution(ib.max()[2] - ib.min()[2] + 1, kNanoVdbMajorantResolution)};
  return MajorantGrid(res[0], res[1], res[2]);
}

}  // namespace

NanoVdbMedium::NanoVdbMedium(const NanoVdbParams& params, const Transform& medium_to_world)
    : world_to_medium_(medium_to_world.inverse()),
      sigma_a_(params.sigma_a),
      sigma_s_(params.sigma_s),
      phase_{params.g},
      le_scale_(params.le_scale),
      temperature_offset_(params.temperature_offset),
      temperature_scale_(params.temperature_scale),
      blackbody_(params.blackbody) {
  check_header(params.path);
  auto grids = std::make_shared<NanoVdbGrids>();
  grids->density_handle = read_float_grid(params.path, params.density_grid);
  if (!grids->density_handle) throw Error(params.path, "", "has no grid named " + quoted(params.density_grid));
  grids->density = grids->density_handle.grid<float>();
  grids->temperature_handle = read_float_grid(params.path, params.temperature_grid);
  grids->temperature = grids->temperature_handle ? grids->temperature_handle.grid<float>() : nullptr;
  if (grids->density->activeVoxelCount() == 0)
    throw Error(params.path, "", "grid " + quoted(params.density_grid) + " has no active voxels");
  Bounds3f bounds = world_bounds(*grids->density);
  if (grids->temperature && grids->temperature->activeVoxelCount() > 0)
    bounds.extend(world_bounds(*grids->temperature));
  box_ = MediumBox(medium_to_world, bounds);
  majorant_ = majorant_for(*grids->density);
  MajorantBuilder(*grids->density, bounds, majorant_).build();
  grids_ = std::move(grids);
}

bool NanoVdbMedium::emissive() const { return grids_->temperature && le_scale_ > 0.0f && !sigma_a_.is_black(); }

MediumProperties NanoVdbMedium::at(Vec3f p) const {
  const Vec3f pm = world_to_medium_.point(p);
  // Negative voxel values (a level set read as density) would make extinction negative: read as empty space.
  const float d = std::max(0.0f, sample_grid(*grids_->density, pm));
  MediumProperties mp{sigma_a_ * d, sigma_s_ * d, Rgb(0.0f)};
  if (grids_->temperature && le_scale_ > 0.0f) {
    const float t = (sample_grid(*grids_->temperature, pm) - temperature_offset_) * temperature_scale_;
    mp.le = emission_at(blackbody_, t) * le_scale_;
  }
  return mp;
}

NanoVdbMedium::Majorants NanoVdbMedium::majorants(const Ray& ray, float tmax) const {
  return box_.majorants(majorant_, ray, tmax, sigma_a_ + sigma_s_);
}

uint64_t NanoVdbMedium::active_voxels() const { return grids_->density->activeVoxelCount(); }

size_t NanoVdbMedium::grid_bytes() const {
  return grids_->density_handle.size() + (grids_->temperature ? grids_->temperature_handle.size() : 0);
}

std::string NanoVdbMedium::describe() const {
  std::string d = "nanovdb " + std::to_string(active_voxels()) + " active voxels, sigma_a " + describe_rgb(sigma_a_) +
                  " sigma_s " + describe_rgb(sigma_s_) + " g " + describe_float(phase_.g) + ", majorant grid " +
                  majorant_.describe();
  if (emissive()) d += ", temperature emission";
  return d;
}

}  // namespace kiln
