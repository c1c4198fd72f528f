// Transmittance by delta tracking and by ratio tracking (both built on sample_collisions, media/tracking.h) against
// Beer-Lambert: through a homogeneous slab, through uniform grids whose optical depth is known in closed form, and
// for a channel other than the tracked one (the chromatic weights). Estimates must agree within 4 standard errors.
#include <gtest/gtest.h>

#include <cmath>

#include "media/tracking.h"

namespace kiln::test {
namespace {

constexpr int kSamples = 200'000;
constexpr double kSigmas = 4.0;

struct Estimate {
  double mean = 0, stderr_ = 0;
};

template <typename F>
Estimate estimate(F&& one, uint64_t seed, int samples = kSamples) {
  Rng rng(seed, 3);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < samples; ++i) {
    const double v = one(rng);
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / samples;
  return {mean, std::sqrt(std::max(0.0, sum2 / samples - mean * mean) / (samples - 1))};
}

// Delta tracking of channel `c` with collisions sampled on channel h: a real collision (probability
// sigma_t / sigma_maj of h) ends the walk with 0; null collisions and the end carry the ratio of c's majorant
// transmittance and null density to h's (1 for c == h).
double delta_tracking(const Medium& m, const Ray& ray, float tmax, int h, int c, Rng& rng) {
  double w = 1.0;
  bool absorbed = false;
  const Rgb t_end = sample_collisions(m, ray, tmax, rng.next_float(), rng, h,
                                      [&](Vec3f, const MediumProperties& mp, Rgb sigma_maj, Rgb t_maj) {
                                        const Rgb sigma_n = sigma_maj - mp.sigma_a - mp.sigma_s;
                                        if (rng.next_float() < 1.0f - sigma_n[h] / sigma_maj[h]) {
                                          absorbed = true;
                                          return false;
                                        }
                                        w *= double(t_maj[c] * sigma_n[c]) / double(t_maj[h] * sigma_n[h]);
                                        return true;
                                      });
  return absorbed ? 0.0 : w * double(t_end[c]) / double(t_end[h]);
}

// Ratio tracking: every collision multiplies the estimate by the null fraction sigma_n / sigma_maj.
double ratio_tracking(const Medium& m, const Ray& ray, float tmax, int h, int c, Rng& rng) {
  double w = 1.0;
  const Rgb t_end = sample_collisions(m, ray, tmax, rng.next_float(), rng, h,
                                      [&](Vec3f, const MediumProperties& mp, Rgb sigma_maj, Rgb t_maj) {
                                        const Rgb sigma_n = sigma_maj - mp.sigma_a - mp.sigma_s;
                                        w *= double(t_maj[c] * sigma_n[c]) / double(t_maj[h] * sigma_maj[h]);
                                        return w > 0.0;
                                      });
  return w * double(t_end[c]) / double(t_end[h]);
}

void expect_beer_lambert(const Medium& m, const Ray& ray, float tmax, int h, int c, double tau, const char* what,
                         int samples = kSamples) {
  const double expected = std::exp(-tau);
  for (const bool ratio : {false, true}) {
    const Estimate e = estimate(
        [&](Rng& rng) { return ratio ? ratio_tracking(m, ray, tmax, h, c, rng) : delta_tracking(m, ray, tmax, h, c, rng); },
        0x5eed + uint64_t(ratio), samples);
    EXPECT_NEAR(e.mean, expected, kSigmas * e.stderr_ + 1e-6)
        << what << (ratio ? ", ratio tracking" : ", delta tracking") << ", tracked channel " << h << ", channel " << c;
  }
}

TEST(Tracking, HomogeneousSlabIsBeerLambert) {
  const Medium m = HomogeneousMedium(Rgb(0.3f), Rgb(0.9f), Rgb(0.0f), 0.0f);
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  expect_beer_lambert(m, ray, 1.5f, 0, 0, 1.2 * 1.5, "homogeneous slab");
}

TEST(Tracking, ChromaticSlabTrackedOnAnotherChannel) {
  // Extinction 0.2, 2 and 20 per unit: every channel estimated from collisions sampled on each other channel.
  const Medium m = HomogeneousMedium(Rgb(0.1f, 1.0f, 10.0f), Rgb(0.1f, 1.0f, 10.0f), Rgb(0.0f), 0.0f);
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  const float length = 0.4f;
  const double sigma[3] = {0.2, 2.0, 20.0};
  // Tracked on blue, a walk passes with probability e^-8 (67 of 200 K): too few to test against.
  for (int h = 0; h < 2; ++h)
    for (int c = 0; c < 3; ++c) expect_beer_lambert(m, ray, length, h, c, sigma[c] * length, "chromatic slab");
}

// A constant lattice of 1 fades to 1/2 at the box's faces over half a voxel (media/sampled_grid.h): along an axis
// of n samples the unit cube holds 1 - 1/(4n) of density.
TEST(Tracking, ConstantGridHasTheFadedOpticalDepth) {
  const int n = 4;
  const Bounds3f box({0, 0, 0}, {2, 1, 1});
  const Medium m = GridMedium(Transform(), box, Rgb(0.4f), Rgb(0.8f), 0.0f,
                              SampledGrid<float>(std::vector<float>(size_t(n * n * n), 1.0f), n, n, n), GridEmission{});
  const Ray ray{{-1, 0.5f, 0.5f}, {1, 0, 0}};
  expect_beer_lambert(m, ray, 10.0f, 1, 1, 1.2 * 2.0 * (1.0 - 0.25 / n), "constant grid");
}

// Samples x + 1/2 along x (n of them): the density is n u inside, and blends with zero over the outer half voxels,
// which hold 3/16 / n (low end) and 3/8 (n - 1/2) / n (high end) of density; the inside holds (n - 1) / 2.
TEST(Tracking, RampGridHasItsClosedFormOpticalDepth) {
  const int n = 8;
  std::vector<float> v;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < n; ++x) v.push_back(float(x) + 0.5f);
  // y and z span 2 samples each; the ray runs through their middle, where both are full.
  const Medium m = GridMedium(Transform::rotate(30.0f, {0, 0, 1}), Bounds3f({0, 0, 0}, {1, 1, 1}), Rgb(0.5f),
                              Rgb(0.0f), 0.0f, SampledGrid<float>(v, n, 2, 2), GridEmission{});
  const double depth = 0.1875 / n + (n - 1) / 2.0 + 0.375 * (n - 0.5) / n;
  const Vec3f dir = Transform::rotate(30.0f, {0, 0, 1}).vector({1, 0, 0});
  const Ray ray{Transform::rotate(30.0f, {0, 0, 1}).point({-0.5f, 0.5f, 0.5f}), dir};
  expect_beer_lambert(m, ray, 10.0f, 0, 0, 0.5 * depth, "ramp grid");
}

TEST(Tracking, ZeroMajorantChannelPassesWithItsTransmittance) {
  // Tracked on a channel without extinction: no collision is sampled, the others carry exp(-sigma d) exactly.
  const Medium m = HomogeneousMedium(Rgb(1.0f, 0.0f, 0.5f), Rgb(0.0f), Rgb(0.0f), 0.0f);
  Rng rng(1, 1);
  const Rgb t = sample_collisions(m, Ray{{0, 0, 0}, {0, 1, 0}}, 2.0f, 0.3f, rng, 1,
                                  [](Vec3f, const MediumProperties&, Rgb, Rgb) { return true; });
  EXPECT_FLOAT_EQ(t.r, std::exp(-2.0f));
  EXPECT_EQ(t.g, 1.0f);
  EXPECT_FLOAT_EQ(t.b, std::exp(-1.0f));
  // An infinite segment through it: zero extinction stays 1, not NaN.
  const Rgb inf = sample_collisions(m, Ray{{0, 0, 0}, {0, 1, 0}}, kInfinity, 0.3f, rng, 1,
                                    [](Vec3f, const MediumProperties&, Rgb, Rgb) { return true; });
  EXPECT_EQ(inf.g, 1.0f);
  EXPECT_EQ(inf.r, 0.0f);
}

// The procedural cloud (its noise, its clamps, its box under a transform) against the optical depth of its own
// density integrated by the midpoint rule, independently of the majorants: random rays through the box, each
// channel tracked on green.
double optical_depth_by_quadrature(const Medium& m, const Ray& ray, float tmax, int c) {
  constexpr int kSteps = 200'000;
  const double dt = double(tmax) / kSteps;
  double tau = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const MediumProperties mp = medium_at(m, ray.at(float((i + 0.5) * dt)));
    tau += double(mp.sigma_a[c] + mp.sigma_s[c]) * dt;
  }
  return tau;
}

TEST(Tracking, CloudTransmittanceMatchesQuadratureOfItsDensity) {
  const Transform to_world = Transform::translate({0.2f, 0.1f, -0.3f}) * Transform::rotate(25.0f, {1, 1, 0});
  const Medium m = CloudMedium(to_world, Bounds3f({-0.2f, -0.2f, 0.0f}, {1.0f, 1.0f, 1.0f}),
                               Rgb(0.1f, 0.2f, 0.4f), Rgb(0.8f, 1.0f, 1.2f), 0.0f, CloudShape{2.0f, 1.0f, 5.0f});
  Rng rng(17, 5);
  constexpr float kLength = 6.0f;  // the rays start 3 units from the box's centre and end beyond it
  for (int i = 0; i < 4; ++i) {
    const Vec3f target = to_world.point({0.4f + 0.3f * (rng.next_float() - 0.5f), 0.2f + 0.8f * rng.next_float(),
                                         0.5f + 0.3f * (rng.next_float() - 0.5f)});
    const Vec3f w = normalize(Vec3f(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
    const Ray ray{target - w * 3.0f, w};
    for (int c = 0; c < 3; ++c) {
      const double tau = optical_depth_by_quadrature(m, ray, kLength, c);
      EXPECT_GT(tau, 0.05) << "ray " << i << " must cross the cloud";
      expect_beer_lambert(m, ray, kLength, 1, c, tau, ("cloud ray " + std::to_string(i)).c_str(), 50'000);
    }
  }
}

}  // namespace
}  // namespace kiln::test
