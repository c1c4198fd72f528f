// Shared pieces of the numerical-stability suite (tests/renderer/stability_*.cpp): a Cornell box built in code on
// an integer grid (so translating it by integers is exact, even 2e5 units from the origin), closed meshes, the
// accelerator parameterisation and image comparisons that know each pixel's noise.
#pragma once
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "renderer/render_util.h"
#include "renderer/accel/accelerator.h"

namespace kiln::test {

// Every stability test runs with both ray-query backends.
class AccelParam : public ::testing::TestWithParam<AccelKind> {
 protected:
  WorldOptions world_options() const {
    WorldOptions o;
    o.accel = GetParam();
    return o;
  }
};
inline std::string accel_name(const ::testing::TestParamInfo<AccelKind>& info) {
  return info.param == AccelKind::Embree ? "Embree" : "Bvh";
}
#define KILN_INSTANTIATE_FOR_BOTH_ACCELS(Suite) \
  INSTANTIATE_TEST_SUITE_P(Accels, Suite, ::testing::Values(AccelKind::Embree, AccelKind::Bvh), accel_name)

// The far-away centre of the issue: coordinates where a float's ulp is 1/64.
inline const Vec3f kFarCentre(148376.0f, 1234.0f, -223423.0f);
// The Cornell box's half-size in grid units: every coordinate below is an integer number of grid units.
inline constexpr float kBoxGrid = 256.0f;

// Materials of the box, by index into SceneDesc::materials.
enum BoxMaterial { kWhite, kRed, kGreen, kGlass, kGlossy, kBoxMaterialCount };

struct BoxPlacement {
  float unit = 1.0f / kBoxGrid;  // world size of one grid unit
  Vec3f offset{0.0f};            // added after scaling
  Vec3f at(float gx, float gy, float gz) const { return Vec3f(gx, gy, gz) * unit + offset; }
};

inline MeshDesc quad_mesh(const std::string& name, Vec3f a, Vec3f b, Vec3f c, Vec3f d, int material) {
  MeshDesc m;
  m.name = name;
  m.positions = {a, b, c, d};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = material;
  return m;
}

// Closed axis-aligned box [lo, hi] with outward winding.
inline MeshDesc box_mesh(const std::string& name, Vec3f lo, Vec3f hi, int material) {
  MeshDesc m;
  m.name = name;
  for (int i = 0; i < 8; ++i) m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  // Faces -x, +x, -y, +y, -z, +z (outward by the right-hand rule).
  m.indices = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
               2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
  m.material = material;
  return m;
}

// A Cornell box (floor, ceiling, back, red and green walls), a closed block, a diffuse sphere, a glass sphere and a
// downward-facing ceiling light, seen from the open front through camera "1". The grid coordinates are integers,
// so with unit 1 and an integer offset every vertex, centre and the camera position are exact floats.
inline SceneDesc cornell_box(const BoxPlacement& at, int resolution, float light_radiance = 15.0f) {
  SceneDesc s;
  s.format = "test";
  s.source_path = "stability_box";
  s.max_recursion_depth = 6;
  BrdfDesc lambert;
  lambert.kind = BrdfKind::Lambert;
  s.brdfs.push_back(lambert);
  BrdfDesc phong;
  phong.kind = BrdfKind::ModifiedPhong;
  phong.normalized = true;
  phong.exponent = 40.0f;
  s.brdfs.push_back(phong);
  auto diffuse = [&](Rgb kd) {
    MaterialDesc m;
    m.brdf = 0;
    m.diffuse = kd;
    return m;
  };
  s.materials.resize(kBoxMaterialCount);
  s.materials[kWhite] = diffuse(Rgb(0.75f));
  s.materials[kRed] = diffuse(Rgb(0.7f, 0.12f, 0.12f));
  s.materials[kGreen] = diffuse(Rgb(0.15f, 0.7f, 0.15f));
  s.materials[kGlass].type = MaterialType::Dielectric;
  s.materials[kGlass].refraction_index = 1.5f;
  s.materials[kGlass].has_refraction_index = true;
  s.materials[kGlossy].brdf = 1;
  s.materials[kGlossy].diffuse = Rgb(0.2f, 0.3f, 0.5f);
  s.materials[kGlossy].specular = Rgb(0.5f);
  for (size_t i = 0; i < s.materials.size(); ++i) s.materials[i].id = int(i + 1);

  const float g = kBoxGrid;
  s.meshes.push_back(quad_mesh("floor", at.at(-g, -g, -g), at.at(-g, -g, g), at.at(g, -g, g), at.at(g, -g, -g), kWhite));
  s.meshes.push_back(quad_mesh("ceiling", at.at(-g, g, -g), at.at(g, g, -g), at.at(g, g, g), at.at(-g, g, g), kWhite));
  s.meshes.push_back(quad_mesh("back", at.at(-g, -g, -g), at.at(g, -g, -g), at.at(g, g, -g), at.at(-g, g, -g), kWhite));
  s.meshes.push_back(quad_mesh("left", at.at(-g, -g, -g), at.at(-g, g, -g), at.at(-g, g, g), at.at(-g, -g, g), kRed));
  s.meshes.push_back(quad_mesh("right", at.at(g, -g, -g), at.at(g, -g, g), at.at(g, g, g), at.at(g, g, -g), kGreen));
  s.meshes.push_back(box_mesh("block", at.at(-180, -255, -170), at.at(-40, 40, -40), kGlossy));
  MeshDesc light = quad_mesh("light", at.at(-64, 255, -64), at.at(64, 255, -64), at.at(64, 255, 64), at.at(-64, 255, 64), -1);
  light.emission = Rgb(light_radiance);  // (v1-v0)x(v2-v0) = -y: emits downwards
  s.meshes.push_back(light);
  SphereDesc diffuse_sphere;
  diffuse_sphere.name = "Sphere diffuse";
  diffuse_sphere.center = at.at(120, -170, -120);
  diffuse_sphere.radius = 80.0f * at.unit;
  diffuse_sphere.material = kWhite;
  s.spheres.push_back(diffuse_sphere);
  SphereDesc glass = diffuse_sphere;
  glass.name = "Sphere glass";
  glass.center = at.at(60, -150, 110);
  glass.radius = 96.0f * at.unit;
  glass.material = kGlass;
  s.spheres.push_back(glass);

  CameraDesc cam;
  cam.id = "1";
  cam.position = at.at(0, 0, 900);
  cam.gaze = {0, 0, -1};
  cam.up = {0, 1, 0};
  cam.use_fov = true;
  cam.fov_y_deg = 38;
  cam.width = cam.height = resolution;
  cam.renderer = RendererKind::PathTracing;
  s.cameras.push_back(cam);
  return s;
}

// Kiln's default path tracer (MIS, roulette after depth 3) with the scene's depth.
inline PathSettings stability_settings(const SceneDesc& s) { return kiln_path_defaults(s); }

struct Rendered {
  Film film;
  RenderStats stats;
  Image mean() const { return film.mean(); }
};

// Renders with the world's feature mask (the integrator specialised as kiln render would).
inline Rendered render_film(const World& w, const CameraDesc& cd, IntegratorSettings s, uint32_t spp,
                            uint64_t seed = 1) {
  s.features = w.features;
  const Camera cam(cd);
  Rendered r{Film(cam.width(), cam.height()), {}};
  RenderOptions ro;
  ro.seed = seed;
  ro.spp_total = spp;
  r.stats = render_samples(w, cam, s, ro, 0, spp, r.film);
  return r;
}

inline bool all_finite_non_negative(const Image& img) {
  for (const Rgb& p : img.pixels())
    if (!p.is_finite() || p.has_negative()) return false;
  return true;
}

// Per-pixel comparison of two renders of the same view: the luminance difference in units of its own standard
// error sqrt(var_a + var_b) (the films' per-pixel variance of the mean, floored by floor_abs so flat black areas
// do not divide by zero). An isolated speckle or a ring of wrong pixels shows up as large |z|.
struct PixelDiffStats {
  double max_z = 0;
  int worst_x = -1, worst_y = -1;
  size_t outliers = 0;  // pixels with |z| > outlier_z
  double mean_a = 0, mean_b = 0;
  double mean_se = 0;   // standard error of mean_a - mean_b for independent noise
};

inline PixelDiffStats compare_films(const Film& a, const Film& b, double outlier_z, double floor_abs) {
  const Image ma = a.mean(), mb = b.mean(), va = a.variance_of_mean(), vb = b.variance_of_mean();
  PixelDiffStats s;
  double var_sum = 0;
  const double n = double(ma.pixels().size());
  for (int y = 0; y < ma.height(); ++y)
    for (int x = 0; x < ma.width(); ++x) {
      const double la = ma.at(x, y).luminance(), lb = mb.at(x, y).luminance();
      const double var = double(va.at(x, y).r) + double(vb.at(x, y).r);
      const double z = std::abs(la - lb) / (std::sqrt(var) + floor_abs);
      if (z > s.max_z) {
        s.max_z = z;
        s.worst_x = x;
        s.worst_y = y;
      }
      s.outliers += z > outlier_z;
      s.mean_a += la / n;
      s.mean_b += lb / n;
      var_sum += var;
    }
  s.mean_se = std::sqrt(var_sum) / n;
  return s;
}

// Image-average luminance and its standard error from the films' per-pixel variance of the mean.
struct MeanEstimate {
  double mean = 0, se = 0;
};
inline MeanEstimate film_mean(const Film& f) {
  const Image m = f.mean(), v = f.variance_of_mean();
  const double n = double(m.pixels().size());
  MeanEstimate e;
  double var = 0;
  for (size_t i = 0; i < m.pixels().size(); ++i) {
    e.mean += m.pixels()[i].luminance() / n;
    var += v.pixels()[i].r;
  }
  e.se = std::sqrt(var) / n;
  return e;
}

// (block mean - expected) / (block standard error) for every block x block square, row by row.
inline std::vector<double> block_z(const Film& f, int block, double expected) {
  const Image m = f.mean(), v = f.variance_of_mean();
  std::vector<double> z;
  for (int by = 0; by < m.height(); by += block)
    for (int bx = 0; bx < m.width(); bx += block) {
      double sum = 0, var = 0, n = 0;
      for (int y = by; y < std::min(by + block, m.height()); ++y)
        for (int x = bx; x < std::min(bx + block, m.width()); ++x) {
          sum += m.at(x, y).luminance();
          var += v.at(x, y).r;
          n += 1;
        }
      z.push_back((sum / n - expected) / (std::sqrt(var) / n + 1e-12));
    }
  return z;
}
inline double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// A closed, watertight sphere-like mesh: an octahedron subdivided `levels` times with shared midpoints, projected
// onto the sphere, outward winding.
inline TriangleMesh closed_sphere_mesh(int levels, Vec3f centre, float radius) {
  std::vector<Vec3f> p = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<uint32_t> idx = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      p.push_back(normalize(p[a] + p[b]));
      return mid[key] = uint32_t(p.size() - 1);
    };
    std::vector<uint32_t> next;
    for (size_t i = 0; i < idx.size(); i += 3) {
      const uint32_t a = idx[i], b = idx[i + 1], c = idx[i + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
    }
    idx = std::move(next);
  }
  TriangleMesh m;
  for (const Vec3f& v : p) m.p.push_back(centre + v * radius);
  m.idx = std::move(idx);
  return m;
}

}  // namespace kiln::test
