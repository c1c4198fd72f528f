// Degenerate input: zero-area triangles, zero-radius spheres, emitters of zero radiance or zero area, a camera
// inside a sphere or inside glass. Real scene files contain all of these (collapsed faces after export, placeholder
// lights); the renderer must produce a finite image without crashing.
#include <gtest/gtest.h>

#include "core/error.h"
#include "renderer/integrators/stability_util.h"

namespace kiln::test {
namespace {

constexpr int kResolution = 24;
constexpr uint32_t kSpp = 8;

class Degenerate : public AccelParam {
 protected:
  // Renders with every strategy family (BRDF-only, NEE, MIS with roulette) and checks the image is finite.
  Image render_all_ways(const SceneDesc& s) {
    const auto w = build_world(s, world_options());
    Image last;
    const std::tuple<bool, bool, bool> modes[] = {{false, false, false}, {true, false, false}, {true, true, true}};
    for (const auto& [nee, mis, rr] : modes) {
      PathSettings st = stability_settings(s);
      st.nee = nee;
      st.mis = mis;
      st.russian_roulette = rr;
      const Rendered r = render_film(*w, s.cameras[0], st, kSpp);
      EXPECT_EQ(r.stats.rays.nan_samples, 0u) << IntegratorSettings(st).describe() << ", first at pixel " << r.stats.nan_x << ","
                                              << r.stats.nan_y;
      last = r.mean();
      EXPECT_TRUE(all_finite_non_negative(last)) << IntegratorSettings(st).describe();
    }
    return last;
  }
};

double mean_luminance(const Image& img) {
  double s = 0;
  for (const Rgb& p : img.pixels()) s += p.luminance();
  return s / double(img.pixels().size());
}

// Why: collapsed faces (three equal vertices, three collinear ones) have a zero normal; shading them, or sampling
// them as part of a light, divides by their zero area or length.
TEST_P(Degenerate, ZeroAreaTrianglesInMeshesAndLights) {
  BoxPlacement at;
  SceneDesc s = cornell_box(at, kResolution);
  MeshDesc junk;
  junk.name = "Mesh degenerate";
  junk.positions = {at.at(0, 0, 0), at.at(0, 0, 0), at.at(0, 0, 0), at.at(-50, 0, 0), at.at(0, 0, 0), at.at(50, 0, 0)};
  junk.indices = {0, 1, 2, 3, 4, 5};  // a point and a segment across the middle of the view
  junk.material = kWhite;
  s.meshes.push_back(junk);
  // A light whose triangles are a real one plus a collapsed one, and a light that is all collapsed.
  MeshDesc light = s.meshes[6];
  ASSERT_EQ(light.name, "light");
  light.name = "light with a collapsed triangle";
  light.positions.push_back(at.at(10, 250, 10));
  light.indices.insert(light.indices.end(), {4, 4, 4});
  s.meshes[6] = light;
  MeshDesc dead_light;
  dead_light.name = "zero-area light";
  dead_light.positions = {at.at(-100, 200, 0), at.at(-80, 200, 0), at.at(-60, 200, 0)};  // collinear
  dead_light.indices = {0, 1, 2};
  dead_light.emission = Rgb(5.0f);
  s.meshes.push_back(dead_light);
  const Image img = render_all_ways(s);
  EXPECT_GT(mean_luminance(img), 0.0);  // the real light still lights the box
}

// Why: a sphere of radius 0 (a placeholder) makes the quadratic degenerate and its normal (p - c)/r undefined;
// black emitters (a sphere, a mesh and a point light of radiance 0) must not enter light selection with a zero
// power that later divides.
TEST_P(Degenerate, ZeroRadiusSpheresAndZeroRadianceLights) {
  BoxPlacement at;
  SceneDesc s = cornell_box(at, kResolution);
  SphereDesc point_sphere;
  point_sphere.name = "Sphere radius 0";
  point_sphere.center = at.at(0, 0, 0);
  point_sphere.radius = 0.0f;
  point_sphere.material = kWhite;
  s.spheres.push_back(point_sphere);
  SphereDesc dark_light;
  dark_light.name = "Sphere light of radiance 0";
  dark_light.center = at.at(-150, 150, 100);
  dark_light.radius = 40.0f * at.unit;
  dark_light.material = -1;
  dark_light.emission = Rgb(0.0f);
  s.spheres.push_back(dark_light);
  MeshDesc dark_mesh_light = quad_mesh("dark light", at.at(150, 250, -50), at.at(200, 250, -50), at.at(200, 250, 0),
                                       at.at(150, 250, 0), -1);
  dark_mesh_light.emission = Rgb(0.0f);
  s.meshes.push_back(dark_mesh_light);
  s.point_lights.push_back(PointLightDesc{at.at(0, 100, 100), Rgb(0.0f)});
  const Image img = render_all_ways(s);
  EXPECT_GT(mean_luminance(img), 0.0);
}

// Why: an emitting sphere of radius 0 has no area to sample (its solid-angle pdf would be 0 or Inf). It emits no
// power, so the world leaves it out of the lights with a warning and the scene renders without NaN.
TEST_P(Degenerate, ZeroRadiusSphereLightIsLeftOut) {
  BoxPlacement at;
  SceneDesc s = cornell_box(at, kResolution);
  SphereDesc point_light;
  point_light.name = "Sphere light radius 0";
  point_light.center = at.at(0, 150, 0);
  point_light.radius = 0.0f;
  point_light.emission = Rgb(100.0f);
  s.spheres.push_back(point_light);
  const auto world = build_world(s, world_options());
  EXPECT_EQ(world->stats.sphere_lights, 0u);
  EXPECT_FALSE(world->warnings.empty());
  const Image img = render_all_ways(s);
  EXPECT_GT(mean_luminance(img), 0.0);
}

// Why: with no light at all (every emitter black) the light selector is empty or all-zero; NEE must skip it.
TEST_P(Degenerate, SceneWhoseOnlyLightIsBlack) {
  BoxPlacement at;
  const SceneDesc s = cornell_box(at, kResolution, 0.0f);
  const Image img = render_all_ways(s);
  EXPECT_EQ(mean_luminance(img), 0.0);
}

// Why: a camera inside a closed diffuse sphere sees only the inside, which no light reaches: the image is black,
// every ray starts inside a shape, and back faces are all the renderer sees.
TEST_P(Degenerate, CameraInsideASphere) {
  BoxPlacement at;
  SceneDesc s = cornell_box(at, kResolution);
  SphereDesc shell;
  shell.name = "Sphere around the camera";
  shell.center = s.cameras[0].position;
  shell.radius = 0.5f;
  shell.material = kWhite;
  s.spheres.push_back(shell);
  const Image img = render_all_ways(s);
  EXPECT_EQ(mean_luminance(img), 0.0);
}

// Why: a camera inside glass starts its paths inside a dielectric (the local frame says "inside" from the first
// hit, exits scale radiance by eta^2 and see total internal reflection); the box must still be visible through it.
TEST_P(Degenerate, CameraInsideGlass) {
  BoxPlacement at;
  SceneDesc s = cornell_box(at, kResolution);
  SphereDesc lens;
  lens.name = "Sphere of glass around the camera";
  lens.center = s.cameras[0].position;
  lens.radius = 1.0f;
  lens.material = kGlass;
  s.spheres.push_back(lens);
  const Image img = render_all_ways(s);
  EXPECT_GT(mean_luminance(img), 0.0);
}

KILN_INSTANTIATE_FOR_BOTH_ACCELS(Degenerate);

}  // namespace
}  // namespace kiln::test
