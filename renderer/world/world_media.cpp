#include "renderer/world/world_media.h"

#include "core/error.h"

namespace kiln {
namespace {

Bounds3f lattice_box(const MediumLattice& l) { return Bounds3f(l.p0, l.p1); }

Medium grid_medium(const MediumDesc& d, const GridMediumDesc& g) {
  const MediumLattice& l = g.lattice;
  GridEmission e;
  e.le = g.le;
  e.le_scale = g.le_scale.size() == 1 ? SampledGrid<float>(g.le_scale, 1, 1, 1)
                                      : SampledGrid<float>(g.le_scale, l.nx, l.ny, l.nz);
  if (!g.temperature.empty()) {
    e.temperature = SampledGrid<float>(g.temperature, l.nx, l.ny, l.nz);
    e.temperature_offset = g.temperature_offset;
    e.temperature_scale = g.temperature_scale;
    e.blackbody = d.blackbody;
  }
  return GridMedium(d.to_world, lattice_box(l), g.sigma_a, g.sigma_s, d.g,
                    SampledGrid<float>(g.density, l.nx, l.ny, l.nz), std::move(e));
}

SampledGrid<Rgb> rgb_lattice(const std::vector<Rgb>& v, const MediumLattice& l) {
  return v.empty() ? SampledGrid<Rgb>() : SampledGrid<Rgb>(v, l.nx, l.ny, l.nz);
}

Medium rgb_grid_medium(const MediumDesc& d, const RgbGridMediumDesc& g) {
  return RgbGridMedium(d.to_world, lattice_box(g.lattice), rgb_lattice(g.sigma_a, g.lattice),
                       rgb_lattice(g.sigma_s, g.lattice), g.scale, rgb_lattice(g.le, g.lattice), g.le_scale, d.g);
}

Medium nanovdb_medium(const MediumDesc& d, const NanoVdbMediumDesc& v) {
  NanoVdbParams p;
  p.path = v.path;
  p.density_grid = v.density_grid;
  p.temperature_grid = v.temperature_grid;
  p.sigma_a = v.sigma_a;
  p.sigma_s = v.sigma_s;
  p.g = d.g;
  p.le_scale = v.le_scale;
  p.temperature_offset = v.temperature_offset;
  p.temperature_scale = v.temperature_scale;
  p.blackbody = d.blackbody;
  return NanoVdbMedium(p, d.to_world);
}

Medium cloud_medium(const MediumDesc& d, const CloudMediumDesc& c) {
  return CloudMedium(d.to_world, Bounds3f(c.p0, c.p1), c.sigma_a, c.sigma_s, d.g,
                     CloudShape{c.density, c.wispiness, c.frequency});
}

void record(const Medium& m, WorldStats& s) {
  s.media.push_back(describe_medium(m));
  std::visit(
      [&](const auto& x) {
        using M = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<M, HomogeneousMedium>) {
          ++s.homogeneous_media;
        } else if constexpr (std::is_same_v<M, CloudMedium>) {
          ++s.cloud_media;
        } else {
          s.majorant_voxels += x.majorant_grid().voxels();
          if constexpr (std::is_same_v<M, GridMedium>) ++s.grid_media;
          if constexpr (std::is_same_v<M, RgbGridMedium>) ++s.rgb_grid_media;
          if constexpr (std::is_same_v<M, NanoVdbMedium>) {
            ++s.nanovdb_media;
            s.medium_grid_bytes += x.grid_bytes();
          }
        }
      },
      m);
}

}  // namespace

Medium build_medium(const MediumDesc& d) {
  try {
    return std::visit(
        [&](const auto& p) -> Medium {
          using P = std::decay_t<decltype(p)>;
          if constexpr (std::is_same_v<P, HomogeneousMediumDesc>) return HomogeneousMedium(p.sigma_a, p.sigma_s, p.le, d.g);
          if constexpr (std::is_same_v<P, GridMediumDesc>) return grid_medium(d, p);
          if constexpr (std::is_same_v<P, RgbGridMediumDesc>) return rgb_grid_medium(d, p);
          if constexpr (std::is_same_v<P, NanoVdbMediumDesc>) return nanovdb_medium(d, p);
          if constexpr (std::is_same_v<P, CloudMediumDesc>) return cloud_medium(d, p);
        },
        d.params);
  } catch (const Error& e) {
    throw Error(d.element, "", e.what());
  }
}

bool scene_uses_media(const SceneDesc& scene) {
  if (scene.media.empty()) return false;
  const auto bounds = [](const MediumInterfaceDesc& m) { return m.inside != m.outside; };
  for (const CameraDesc& c : scene.cameras)
    if (c.medium >= 0) return true;
  for (const MeshDesc& m : scene.meshes)
    if (m.visible && bounds(m.media)) return true;
  for (const SphereDesc& s : scene.spheres)
    if (bounds(s.media)) return true;
  for (const InstanceDesc& i : scene.instances)
    if (bounds(i.media)) return true;
  for (const QuadricDesc& q : scene.quadrics)
    if (bounds(q.media)) return true;
  return false;
}

void build_world_media(const SceneDesc& scene, World& w) {
  w.media.reserve(scene.media.size());
  for (const MediumDesc& d : scene.media) {
    w.media.push_back(build_medium(d));
    record(w.media.back(), w.stats);
  }
}

}  // namespace kiln
