// Stiff materials and lights: exponents of 1e5, refractive indices of 1.0001 and 10, total internal reflection, a
// light a million times brighter than its neighbour. These push pdfs, Fresnel terms and MIS weights to the edge
// of float range, where a NaN, an Inf or a silent energy gain appears first.
#include <gtest/gtest.h>

#include "renderer/integrators/stability_util.h"

namespace kiln::test {
namespace {

constexpr float kFurnaceAlbedo = 0.5f;
constexpr double kFurnaceRadiance = 1.0 / (1.0 - kFurnaceAlbedo);  // Le = 1 everywhere, unbounded depth
constexpr int kResolution = 32;
constexpr int kBlock = 8;
// Block means are averages of 64 pixels x spp paths: 5 standard errors is a one-in-a-million miss per block.
constexpr double kMaxBlockZ = 5.0;
constexpr double kMaxMeanZ = 4.5;
constexpr float kStiffExponent = 1e5f;

class Stiff : public AccelParam {};

int add_material(SceneDesc& s, MaterialDesc m) {
  m.id = int(s.materials.size() + 1);
  s.materials.push_back(m);
  return int(s.materials.size() - 1);
}

int add_brdf(SceneDesc& s, BrdfKind kind, float exponent, std::optional<float> eta = std::nullopt) {
  BrdfDesc b;
  b.id = int(s.brdfs.size() + 1);
  b.kind = kind;
  b.exponent = exponent;
  b.normalized = true;
  b.refractive_index = eta;
  s.brdfs.push_back(b);
  return int(s.brdfs.size() - 1);
}

void add_sphere(SceneDesc& s, Vec3f c, float r, int material) {
  SphereDesc d;
  d.name = "Sphere " + std::to_string(s.spheres.size() + 1);
  d.center = c;
  d.radius = r;
  d.material = material;
  s.spheres.push_back(d);
}

int glass(SceneDesc& s, float eta) {
  MaterialDesc m;
  m.type = MaterialType::Dielectric;
  m.refraction_index = eta;
  m.has_refraction_index = true;
  return add_material(s, m);
}

SceneDesc furnace_with_camera_view(int res) {
  SceneDesc s = furnace_box(kFurnaceAlbedo, Rgb(1.0f));
  s.cameras[0].width = s.cameras[0].height = res;
  return s;
}

// Glass spheres of eta 10 and 1.0001 and a glass cube (eta 1.5: internal rays beyond 41.8 degrees are totally
// reflected) in front of the camera.
SceneDesc furnace_with_glass(int res) {
  SceneDesc s = furnace_with_camera_view(res);
  add_sphere(s, {-0.45f, 0.3f, -0.5f}, 0.3f, glass(s, 10.0f));
  add_sphere(s, {0.35f, 0.35f, -0.6f}, 0.3f, glass(s, 1.0001f));
  s.meshes.push_back(box_mesh("cube", {-0.2f, -0.8f, -0.7f}, {0.4f, -0.2f, -0.1f}, glass(s, 1.5f)));
  return s;
}

PathSettings unbounded(DirectionSampling dirs, bool nee, bool mis) {
  PathSettings st;
  st.directions = dirs;
  st.nee = nee;
  st.mis = mis;
  st.russian_roulette = true;
  st.max_depth = -1;
  return st;
}

// Why: inside a furnace of uniform radiance L0 a lossless dielectric is invisible (reflection + refraction
// weights sum to one, and the 1/eta^2 radiance scaling undoes itself on the way out), so every pixel must be L0
// for eta = 10 (Fresnel reflectance 67%), eta = 1.0001 (almost pure transmission, sin ratios near 1) and a glass
// cube where most internal paths are totally reflected. A wrong Fresnel branch, a TIR path lost or a NaN
// from an arcsin/sqrt at the critical angle shows up as a block off L0.
// A deep depth cap instead of roulette keeps every path weight bounded, so the per-block standard errors are
// trustworthy; truncating at kDeepDepth bounces changes L0 by less than 1e-4.
TEST_P(Stiff, DielectricsVanishInAFurnace) {
  constexpr int kDeepDepth = 24;
  SceneDesc s = furnace_with_glass(kResolution);
  const auto w = build_world(s, world_options());
  // Kiln's path tracer samples one Fresnel branch; the course path tracer follows both, each with its weight.
  PathSettings kiln = unbounded(DirectionSampling::Brdf, true, true);
  kiln.russian_roulette = false;
  kiln.max_depth = kDeepDepth;
  CoursePathSettings course;
  course.importance_sampling = course.nee = true;
  course.max_depth = kDeepDepth;
  for (const bool split : {false, true}) {
    const IntegratorSettings st = split ? IntegratorSettings(course) : IntegratorSettings(kiln);
    const Rendered r = render_film(*w, s.cameras[0], st, 64);
    EXPECT_EQ(r.stats.rays.nan_samples, 0u);
    EXPECT_TRUE(all_finite_non_negative(r.mean()));
    const MeanEstimate m = film_mean(r.film);
    EXPECT_NEAR(m.mean, kFurnaceRadiance, kMaxMeanZ * m.se + 1e-4) << "split " << split << ": +- " << m.se;
    EXPECT_LT(max_abs(block_z(r.film, kBlock, kFurnaceRadiance)), kMaxBlockZ) << "split " << split;
  }
}

// Why: the same furnace with unbounded depth and Russian roulette: still unbiased and finite, and no block off L0.
// renderer/integrators/path_tracer.cpp decides survival on beta times the product of eta^2 over transmissions (pbrt-v4's
// etaScale); deciding on beta alone would kill ~99% of the paths inside eta = 10 glass and make the survivors
// rare heavy samples.
TEST_P(Stiff, DielectricsWithRouletteStayUnbiased) {
  SceneDesc s = furnace_with_glass(kResolution);
  const auto w = build_world(s, world_options());
  const Rendered r = render_film(*w, s.cameras[0], unbounded(DirectionSampling::Brdf, true, true), 64);
  EXPECT_EQ(r.stats.rays.nan_samples, 0u);
  EXPECT_TRUE(all_finite_non_negative(r.mean()));
  const MeanEstimate m = film_mean(r.film);
  EXPECT_NEAR(m.mean, kFurnaceRadiance, kMaxMeanZ * m.se + 1e-4) << "+- " << m.se;
  EXPECT_LT(max_abs(block_z(r.film, kBlock, kFurnaceRadiance)), kMaxBlockZ);
}

// Why: a glossy lobe of exponent 1e5 is a near-delta peak (normalisation ~1.6e4, cos^p underflowing a degree
// away). It must not create energy: in the furnace nothing can be brighter than L0 for albedo <= 1. And MIS
// (which evaluates the peak's pdf for light samples) must agree with pure BRDF sampling on the picture.
TEST_P(Stiff, NarrowGlossyLobesStayBelowTheFurnaceBound) {
  SceneDesc s = furnace_with_camera_view(kResolution);
  auto glossy = [&](BrdfKind kind, std::optional<float> eta = std::nullopt) {
    MaterialDesc m;
    m.brdf = add_brdf(s, kind, kStiffExponent, eta);
    m.specular = Rgb(1.0f);
    return add_material(s, m);
  };
  add_sphere(s, {-0.45f, 0.3f, -0.5f}, 0.3f, glossy(BrdfKind::ModifiedPhong));
  add_sphere(s, {0.35f, 0.35f, -0.6f}, 0.3f, glossy(BrdfKind::ModifiedBlinnPhong));
  add_sphere(s, {0.1f, -0.5f, -0.5f}, 0.3f, glossy(BrdfKind::TorranceSparrow, 1.5f));
  const auto w = build_world(s, world_options());
  const Rendered mis = render_film(*w, s.cameras[0], unbounded(DirectionSampling::Brdf, true, true), 64, 1);
  const Rendered brdf = render_film(*w, s.cameras[0], unbounded(DirectionSampling::Brdf, false, false), 64, 2);
  for (const Rendered* r : {&mis, &brdf}) {
    EXPECT_EQ(r->stats.rays.nan_samples, 0u);
    EXPECT_TRUE(all_finite_non_negative(r->mean()));
    for (double z : block_z(r->film, kBlock, kFurnaceRadiance)) EXPECT_LT(z, kMaxBlockZ) << "a block brighter than L0";
  }
  const MeanEstimate a = film_mean(mis.film), b = film_mean(brdf.film);
  EXPECT_LT(a.mean, kFurnaceRadiance + kMaxMeanZ * a.se);
  EXPECT_GT(a.mean, 0.5 * kFurnaceRadiance);  // the walls alone (radiance L0) cover most of the view
  EXPECT_NEAR(a.mean, b.mean, kMaxMeanZ * std::hypot(a.se, b.se)) << "mis " << a.mean << ", brdf " << b.mean;
}

// Why: a tiny sphere light of radiance 1e6 next to a dim area light gives light-selection pmfs, solid-angle pdfs
// and MIS weights spanning ~12 orders of magnitude. Nothing may overflow, and NEE and MIS (both unbiased, with
// different weights) must agree on the picture.
TEST_P(Stiff, TinyBrightLightNextToADimOne) {
  BoxPlacement at;
  SceneDesc s = cornell_box(at, kResolution, 0.05f);
  SphereDesc tiny;
  tiny.name = "Sphere tiny light";
  tiny.center = at.at(100, 200, 0);
  tiny.radius = 1e-3f;
  tiny.emission = Rgb(1e6f);
  s.spheres.push_back(tiny);
  const auto w = build_world(s, world_options());
  PathSettings st = stability_settings(s);
  st.russian_roulette = false;
  PathSettings nee = st;
  nee.mis = false;
  const Rendered a = render_film(*w, s.cameras[0], st, 64, 1);
  const Rendered b = render_film(*w, s.cameras[0], nee, 64, 2);
  for (const Rendered* r : {&a, &b}) {
    EXPECT_EQ(r->stats.rays.nan_samples, 0u);
    EXPECT_TRUE(all_finite_non_negative(r->mean()));
  }
  const MeanEstimate ma = film_mean(a.film), mb = film_mean(b.film);
  EXPECT_GT(ma.mean, 0.0);
  EXPECT_NEAR(ma.mean, mb.mean, kMaxMeanZ * std::hypot(ma.se, mb.se)) << "mis " << ma.mean << ", nee " << mb.mean;
}

KILN_INSTANTIATE_FOR_BOTH_ACCELS(Stiff);

}  // namespace
}  // namespace kiln::test
