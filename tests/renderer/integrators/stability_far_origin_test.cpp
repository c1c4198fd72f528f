// Far from the origin a float's ulp grows (1/64 at 2.2e5): naive hit points, sphere roots or spawn offsets then
// break into speckles (self-shadowing), rings (sphere intersection losing its discriminant) or light leaks.
#include <gtest/gtest.h>

#include "renderer/accel/surface_point.h"
#include "renderer/integrators/stability_util.h"

namespace kiln::test {
namespace {

constexpr int kResolution = 48;
constexpr uint32_t kSpp = 16;
// |difference| in units of the pixel's own standard error beyond which a pixel counts as an outlier: under
// Gaussian noise 6 sigma happens once in 5e8 pixels, so any such pixel is a defect (a speckle or a ring).
constexpr double kOutlierZ = 6.0;
constexpr double kMaxEscapeRate = 2e-5;

class FarOrigin : public AccelParam {};

// Why: the same box rendered at the origin and translated to (148376, 1234, -223423) must be the same picture.
// The translation is exact (integer grid), so any pixel that differs beyond its noise is the renderer's arithmetic
// failing at large coordinates.
TEST_P(FarOrigin, TranslatedSceneRendersTheSameImage) {
  BoxPlacement near_origin, far_away;
  near_origin.unit = far_away.unit = 1.0f;  // half-size 256: ulps of 1/64 far away are 1/16384 of the box
  far_away.offset = kFarCentre;
  const SceneDesc a = cornell_box(near_origin, kResolution), b = cornell_box(far_away, kResolution);
  const auto wa = build_world(a, world_options()), wb = build_world(b, world_options());
  const PathSettings s = stability_settings(a);
  // Same seed: both renders draw the same random numbers, so they differ only where the arithmetic does.
  const Rendered ra = render_film(*wa, a.cameras[0], s, kSpp, 3);
  const Rendered rb = render_film(*wb, b.cameras[0], s, kSpp, 3);
  EXPECT_EQ(ra.stats.rays.nan_samples, 0u);
  EXPECT_EQ(rb.stats.rays.nan_samples, 0u);

  const PixelDiffStats d = compare_films(ra.film, rb.film, kOutlierZ, 1e-4);
  EXPECT_EQ(d.outliers, 0u) << "worst pixel " << d.worst_x << "," << d.worst_y << " at " << d.max_z << " sigma";
  // No systematic brightening or darkening (leaks, acne) either: the image means agree within noise.
  EXPECT_NEAR(d.mean_b, d.mean_a, 4.0 * d.mean_se) << "mean luminance at the origin " << d.mean_a << ", far " << d.mean_b;
  // And the test can fail: a single bright speckle in an otherwise identical image is caught.
  Film speckled = ra.film;
  PixelSum& p = speckled.at(kResolution / 2, kResolution / 2);
  p.r = p.g = p.b = 2.0 * p.n;
  p.lum2 = 4.0 * p.n;
  EXPECT_GE(compare_films(ra.film, speckled, kOutlierZ, 1e-4).outliers, 1u);
}

// Shoots rays from random points inside closed surfaces centred far from the origin: none may find a gap.
size_t escapes_from_inside(const Accelerator& acc, Vec3f centre, float inner_radius, size_t n, uint64_t seed) {
  Rng rng(seed, 11);
  size_t escapes = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3f o = centre + sample_uniform_sphere(rng.next_2d()) * (inner_radius * std::cbrt(rng.next_float()));
    const Vec3f d = sample_uniform_sphere(rng.next_2d());
    Hit h;
    if (!acc.intersect(Ray{o, d}, h) || !acc.occluded(Ray{o, d})) ++escapes;
  }
  return escapes;
}

// Why: a watertight mesh or sphere must stay closed where coordinates are coarse; one escaped camera or bounce
// ray in a closed room is a bright speckle (it sees the background) or a light leak.
TEST_P(FarOrigin, RaysFromInsideClosedSurfacesNeverEscape) {
  constexpr size_t kRays = 60000;
  constexpr float kRadius = 200.0f;
  WorldGeometry g;
  g.meshes.push_back(closed_sphere_mesh(4, kFarCentre, kRadius));
  g.shapes.push_back({ShapeKind::Mesh, 0});
  const auto mesh_acc = make_accelerator(GetParam(), g);
  // The flat facets lie inside the circumscribed sphere: keep origins within the inscribed radius.
  const size_t mesh_escapes = escapes_from_inside(*mesh_acc, kFarCentre, 0.97f * kRadius, kRays, 1);
  EXPECT_LE(double(mesh_escapes), kMaxEscapeRate * kRays) << mesh_escapes << " of " << kRays << " escaped the mesh";

  WorldGeometry gs;
  gs.spheres.push_back(SphereShape{kFarCentre, kRadius, Transform{}});
  gs.shapes.push_back({ShapeKind::Sphere, 0});
  const auto sphere_acc = make_accelerator(GetParam(), gs);
  const size_t sphere_escapes = escapes_from_inside(*sphere_acc, kFarCentre, kRadius, kRays, 2);
  EXPECT_LE(double(sphere_escapes), kMaxEscapeRate * kRays) << sphere_escapes << " of " << kRays << " escaped the sphere";
}

// Why: a path bouncing inside a closed object continues from reconstructed hit points through spawn_ray; the
// ulp-scaled offset must keep every continuation inside (an offset past the surface escapes, one too small
// re-hits the same triangle at t ~ 0 and leaks through it).
TEST_P(FarOrigin, BouncesInsideAClosedMeshStayInside) {
  constexpr int kWalks = 4000, kBounces = 12;
  constexpr float kRadius = 300.0f;
  WorldGeometry g;
  g.meshes.push_back(closed_sphere_mesh(3, kFarCentre, kRadius));
  g.shapes.push_back({ShapeKind::Mesh, 0});
  g.meshes.push_back(closed_sphere_mesh(2, kFarCentre + Vec3f(40, -60, 20), 90.0f));  // an obstacle inside
  g.shapes.push_back({ShapeKind::Mesh, 1});
  const auto acc = make_accelerator(GetParam(), g);
  Rng rng(5, 5);
  size_t rays = 0, escapes = 0;
  for (int w = 0; w < kWalks; ++w) {
    Ray r{kFarCentre + Vec3f(-150, 100, 0), sample_uniform_sphere(rng.next_2d())};
    for (int b = 0; b < kBounces; ++b) {
      Hit h;
      ++rays;
      if (!acc->intersect(r, h)) {
        ++escapes;
        break;
      }
      const Vec3f p = surface_point(g, r, h).p;
      const Vec3f ng = normalize(h.ng);
      // Diffuse-like bounce back into the side the ray came from.
      Vec3f n = dot(ng, r.d) < 0.0f ? ng : -ng;
      Vec3f d = sample_uniform_sphere(rng.next_2d());
      if (dot(d, n) < 0.0f) d = -d;
      r = spawn_ray(p, ng, d);
    }
  }
  EXPECT_LE(double(escapes), kMaxEscapeRate * double(rays)) << escapes << " of " << rays << " bounce rays escaped";
}

KILN_INSTANTIATE_FOR_BOTH_ACCELS(FarOrigin);

}  // namespace
}  // namespace kiln::test
