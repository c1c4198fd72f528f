// The NanoVDB medium against the uniform grid holding the same lattice: a file written through NanoVDB's own
// builder must read back as the same density everywhere (uncompressed and ZIP-compressed), with a majorant grid
// that bounds it; broken files are errors that name the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/rng.h"
#include "media/emission_table.h"
#include "media/majorant_check.h"
#include "media/medium.h"
#include "support/nanovdb_file.h"

namespace kiln::test {
namespace {

std::string tmp(const std::string& name) {
  const std::string d = std::string(KILN_TEST_TMP) + "/media";
  std::filesystem::create_directories(d);
  return d + "/" + name;
}

// A smooth blob on an n^3 lattice whose outer layer is zero, so that the two media's different boxes (the uniform
// grid's [p0, p1], NanoVDB's voxel-cornered world box half a voxel further on) hold the same field.
struct Blob {
  int n = 12;
  Vec3f p0{-1.0f, 0.5f, 2.0f};
  float size = 3.0f;
  std::vector<float> values;
  Blob() {
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const bool border = x == 0 || y == 0 || z == 0 || x == n - 1 || y == n - 1 || z == n - 1;
          const float fx = float(x) / float(n - 1) - 0.4f, fy = float(y) / float(n - 1) - 0.5f,
                      fz = float(z) / float(n - 1) - 0.6f;
          values.push_back(border ? 0.0f : 3.0f * std::exp(-6.0f * (fx * fx + fy * fy + fz * fz)) + 0.2f * float(x % 3));
        }
  }
  float voxel() const { return size / float(n); }
  NanoVdbLattice lattice() const {
    NanoVdbLattice l;
    l.values = values;
    l.nx = l.ny = l.nz = n;
    for (int a = 0; a < 3; ++a) l.origin[a] = p0[a] + 0.5 * voxel();  // voxel x sits at p0 + (x + 1/2) h
    l.voxel = voxel();
    return l;
  }
  GridMedium grid(const Transform& to_world) const {
    return GridMedium(to_world, Bounds3f(p0, p0 + Vec3f(size)), Rgb(0.3f, 0.5f, 0.7f), Rgb(1.0f, 0.8f, 0.2f), 0.0f,
                      SampledGrid<float>(values, n, n, n), GridEmission{});
  }
};

NanoVdbParams params(const std::string& path) {
  NanoVdbParams p;
  p.path = path;
  p.sigma_a = Rgb(0.3f, 0.5f, 0.7f);
  p.sigma_s = Rgb(1.0f, 0.8f, 0.2f);
  return p;
}

Transform placement() { return Transform::translate({0.5f, 0, -1}) * Transform::rotate(20.0f, {0, 1, 1}); }

void expect_same_density(const NanoVdbMedium& vdb, const GridMedium& grid, const Blob& b) {
  Rng rng(9, 9);
  for (int i = 0; i < 20000; ++i) {
    // Points over the blob's box and a margin around it.
    const Vec3f local = b.p0 + Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) * (b.size * 1.2f) -
                        Vec3f(0.1f * b.size);
    const Vec3f p = placement().point(local);
    const MediumProperties a = vdb.at(p), g = grid.at(p);
    ASSERT_NEAR(a.sigma_a.g, g.sigma_a.g, 1e-4f) << "at " << local.x << " " << local.y << " " << local.z;
    ASSERT_NEAR(a.sigma_s.r, g.sigma_s.r, 1e-4f);
  }
}

TEST(NanoVdbMedium, ReadsTheLatticeItWasWrittenWith) {
  const Blob b;
  const std::string plain = tmp("blob.nvdb"), zipped = tmp("blob-zip.nvdb");
  write_nanovdb(plain, {b.lattice()});
  write_nanovdb(zipped, {b.lattice()}, nanovdb::io::Codec::ZIP);
  const GridMedium grid = b.grid(placement());
  for (const std::string& path : {plain, zipped}) {
    SCOPED_TRACE(path);
    const NanoVdbMedium vdb(params(path), placement());
    EXPECT_EQ(vdb.active_voxels(), uint64_t(b.n * b.n * b.n));
    expect_same_density(vdb, grid, b);
  }
}

TEST(NanoVdbMedium, MajorantGridBoundsTheDensity) {
  const Blob b;
  const std::string path = tmp("blob.nvdb");
  write_nanovdb(path, {b.lattice()});
  const NanoVdbMedium vdb(params(path), placement());
  EXPECT_EQ(vdb.majorant_grid().res(0), b.n);
  Rng rng(3, 1);
  MajorantCheck check;
  for (int i = 0; i < 3000; ++i) {
    const Vec3f o = placement().point(b.p0 + Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) * b.size * 3.0f -
                                      Vec3f(b.size));
    const Vec3f target = placement().point(b.p0 + Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) * b.size);
    check_majorants(vdb, Ray{o, normalize(target - o)}, 100.0f, 4, check);
  }
  EXPECT_EQ(check.worst_excess, 0.0f);
  EXPECT_GT(check.points, 5000);
}

// A step from 0 to 5 exactly where NanoVDB's 8^3 leaves meet (x = 8): points just below the step interpolate the
// upper leaf's values, so its maximum must reach the majorant cells on both sides of the boundary.
TEST(NanoVdbMedium, MajorantsReachAcrossLeafBoundaries) {
  NanoVdbLattice l;
  l.nx = l.ny = l.nz = 16;
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) l.values.push_back(x >= 8 ? 5.0f : 0.0f);
  const std::string path = tmp("step.nvdb");
  write_nanovdb(path, {l});
  const NanoVdbMedium vdb(params(path), Transform());
  Rng rng(6, 2);
  MajorantCheck check;
  for (int i = 0; i < 500; ++i) {
    // Rays along +x and -x through the grid, at random heights.
    const Vec3f o(i % 2 ? -1.0f : 17.0f, 0.5f + 14.0f * rng.next_float(), 0.5f + 14.0f * rng.next_float());
    check_majorants(vdb, Ray{o, Vec3f(i % 2 ? 1.0f : -1.0f, 0.0f, 0.0f)}, 100.0f, 16, check);
  }
  EXPECT_EQ(check.worst_excess, 0.0f) << "at x " << check.worst_at.x;
  EXPECT_GT(check.points, 10000);
}

TEST(NanoVdbMedium, ReadsTemperatureBesideDensity) {
  const Blob b;
  NanoVdbLattice t = b.lattice();
  t.name = "temperature";
  for (float& v : t.values) v = 1000.0f;
  const std::string path = tmp("blob-fire.nvdb");
  write_nanovdb(path, {b.lattice(), t});
  NanoVdbParams p = params(path);
  p.blackbody.assign(kEmissionTableSize, Rgb(2.0f, 1.0f, 0.5f));
  p.le_scale = 3.0f;
  const NanoVdbMedium vdb(p, Transform());
  EXPECT_TRUE(vdb.emissive());
  const Vec3f centre = b.p0 + Vec3f(0.5f * b.size);
  EXPECT_EQ(vdb.at(centre).le, Rgb(6.0f, 3.0f, 1.5f));
  // Without a temperature grid the medium does not emit.
  const std::string density_only = tmp("blob.nvdb");
  write_nanovdb(density_only, {b.lattice()});
  EXPECT_FALSE(NanoVdbMedium(params(density_only), Transform()).emissive());
}

void expect_error(const std::string& path, const std::string& needle) {
  try {
    const NanoVdbMedium m(params(path), Transform());
    ADD_FAILURE() << path << ": no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(NanoVdbMedium, BrokenFilesAreErrorsNamingThem) {
  expect_error(tmp("does-not-exist.nvdb"), "cannot open");
  const std::string text = tmp("not-nanovdb.nvdb");
  std::ofstream(text) << "# a pbrt file, not a volume\nShape \"sphere\"\n";
  expect_error(text, "not a NanoVDB file");
  NanoVdbLattice smoke = Blob().lattice();
  smoke.name = "smoke";
  const std::string other = tmp("smoke-only.nvdb");
  write_nanovdb(other, {smoke});
  expect_error(other, "no grid named \"density\"");
  // The first half of a valid file.
  const std::string whole = tmp("blob.nvdb"), cut = tmp("truncated.nvdb");
  write_nanovdb(whole, {Blob().lattice()});
  std::filesystem::copy_file(whole, cut, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::resize_file(cut, std::filesystem::file_size(whole) / 2);
  expect_error(cut, "NanoVDB cannot read it");
}

}  // namespace
}  // namespace kiln::test
