// Delta BSDFs (mirror, dielectric, conductor), the Material mixture of surface and delta parts, and the course
// roughness perturbation.
#include <gtest/gtest.h>

#include <vector>

#include "brdf_test_util.h"
#include "materials/fresnel.h"
#include "support/chi2.h"

namespace kiln::test {
namespace {

constexpr float kEtas[] = {1.0001f, 1.33f, 1.5f, 2.4f, 10.0f};
constexpr float kCosines[] = {1.0f, 0.7f, 0.2f, 1e-3f, 1e-6f};

Material delta_material(const DeltaBsdf& d) {
  Material m;
  m.delta = d;
  return m;
}

TEST(Dielectric, ReflectPlusTransmitIsOne) {
  // Energy: R + T = 1 where T is the transmitted weight with the radiance scaling 1/etap^2 undone.
  for (float eta : kEtas)
    for (float c : kCosines)
      for (float side : {1.0f, -1.0f}) {
        const Vec3f wo = direction_at(side * c, 0.5);
        SpecularBranch b[2];
        const int n = Dielectric{eta}.branches(wo, b);
        ASSERT_GE(n, 1);
        double energy = 0.0, prob = 0.0;
        for (int i = 0; i < n; ++i) {
          energy += b[i].weight.r * (b[i].transmission ? b[i].etap * b[i].etap : 1.0f);
          prob += b[i].probability;
          EXPECT_EQ(b[i].weight.r, b[i].weight.g);
          if (b[i].transmission) {
            EXPECT_LT(b[i].wi.z * wo.z, 0.0f);
            EXPECT_FLOAT_EQ(b[i].etap, side > 0 ? eta : 1.0f / eta);
          } else {
            EXPECT_EQ(b[i].wi, reflect_z(wo));
          }
        }
        EXPECT_NEAR(energy, 1.0, 1e-6) << "eta " << eta << " cos " << side * c;
        EXPECT_NEAR(prob, 1.0, 1e-6);
      }
}

TEST(Dielectric, ReflectionWeightIsFresnel) {
  SpecularBranch b[2];
  ASSERT_EQ(Dielectric{1.5f}.branches(direction_at(0.5), b), 2);
  EXPECT_NEAR(b[0].weight.r, 0.0891867f, 1e-6f);
  EXPECT_NEAR(b[1].weight.r, (1.0f - 0.0891867f) / (1.5f * 1.5f), 1e-6f);
}

TEST(Dielectric, TotalInternalReflectionReflectsEverything) {
  for (float eta : {1.0001f, 1.5f, 10.0f}) {
    const float cos_critical = std::sqrt(1.0f - 1.0f / (eta * eta));
    for (float c : {cos_critical * 0.99f, cos_critical * 0.5f, 1e-6f}) {
      const Vec3f wo = direction_at(-c, 0.2);
      SpecularBranch b[2];
      ASSERT_EQ(Dielectric{eta}.branches(wo, b), 1) << eta << " " << c;
      EXPECT_FALSE(b[0].transmission);
      EXPECT_EQ(b[0].weight, Rgb(1.0f));
      EXPECT_EQ(b[0].wi, reflect_z(wo));
    }
  }
}

TEST(Dielectric, IndexOneTransmitsStraightThrough) {
  const Vec3f wo = direction_at(0.3, 1.0);
  SpecularBranch b[2];
  ASSERT_EQ(Dielectric{1.0f}.branches(wo, b), 1);
  EXPECT_TRUE(b[0].transmission);
  EXPECT_NEAR(b[0].wi.x, -wo.x, 1e-6f);
  EXPECT_NEAR(b[0].wi.z, -wo.z, 1e-6f);
  EXPECT_FLOAT_EQ(b[0].weight.r, 1.0f);
}

TEST(Dielectric, RadianceScalingCancelsThroughAnObject) {
  // Entering scales by (1-R)/eta^2, leaving along the reversed refracted ray by (1-R')eta^2 with R' = R.
  for (float eta : kEtas)
    for (float c : {1.0f, 0.6f, 0.1f}) {
      const Vec3f wo = direction_at(c, 0.1);
      SpecularBranch in[2], out[2];
      ASSERT_EQ(Dielectric{eta}.branches(wo, in), 2);
      const SpecularBranch& t = in[1];
      ASSERT_TRUE(t.transmission);
      const int n = Dielectric{eta}.branches(t.wi, out);  // looking back out along the refracted ray
      ASSERT_EQ(n, 2);
      const float r = in[0].weight.r;
      EXPECT_NEAR(out[0].weight.r, r, 2e-5f);
      EXPECT_NEAR(t.weight.r * out[1].weight.r, sqr(1.0f - r), 2e-5f) << eta << " " << c;
    }
}

TEST(Dielectric, SamplingPicksBranchesByFresnel) {
  const Material glass = delta_material(Dielectric{1.5f});
  for (float c : {0.9f, 0.2f, 0.02f}) {
    const Vec3f wo = direction_at(c, 0.4);
    SpecularBranch b[2];
    ASSERT_EQ(Dielectric{1.5f}.branches(wo, b), 2);
    std::vector<uint64_t> counts(2, 0);
    Rng rng(9, uint64_t(c * 1000));
    for (int i = 0; i < 100000; ++i) {
      const auto s = glass.sample(wo, rng.next_float(), rng.next_2d());
      ASSERT_TRUE(s);
      ASSERT_TRUE(s->is_specular());
      const Rgb w = s->f * (std::abs(s->wi.z) / s->pdf);
      if (s->is_transmission()) {
        ++counts[1];
        EXPECT_NEAR(w.r, 1.0f / (1.5f * 1.5f), 1e-5f);
        EXPECT_FLOAT_EQ(s->eta, 1.5f);
      } else {
        ++counts[0];
        EXPECT_NEAR(w.r, 1.0f, 1e-5f);
      }
    }
    const double probs[] = {b[0].probability, b[1].probability};
    const Chi2Result r = chi2_discrete(counts, probs);
    EXPECT_TRUE(r.passed) << r.message;
  }
}

TEST(Mirror, ReflectsWithTheMirrorColourOnBothSides) {
  const Rgb km(0.9f, 0.5f, 0.1f);
  const Material m = delta_material(Mirror{km});
  for (float c : {0.8f, 1e-6f, -0.4f}) {
    const Vec3f wo = direction_at(c, 2.0);
    DeltaBranch b[2];
    ASSERT_EQ(m.delta_branches(wo, b), 1);
    EXPECT_EQ(b[0].wi, reflect_z(wo));
    EXPECT_EQ(b[0].weight, km);
    const auto s = m.sample(wo, 0.3f, {0.1f, 0.9f});
    ASSERT_TRUE(s);
    EXPECT_TRUE(s->is_specular());
    EXPECT_FALSE(s->is_transmission());
    EXPECT_EQ(s->wi, reflect_z(wo));
    const Rgb w = s->f * (std::abs(s->wi.z) / s->pdf);
    EXPECT_NEAR(w.r, km.r, 1e-5f * (1 + km.r));
    EXPECT_NEAR(w.b, km.b, 1e-5f);
    EXPECT_TRUE(m.eval(wo, s->wi).is_black());
    EXPECT_EQ(m.pdf(wo, s->wi), 0.0f);
  }
}

TEST(Conductor, WeightIsMirrorColourTimesComplexFresnel) {
  const Rgb km(1.0f, 0.86f, 0.57f);
  const Material m = delta_material(Conductor{km, 0.37f, 2.82f});
  DeltaBranch b[2];
  ASSERT_EQ(m.delta_branches(direction_at(0.5), b), 1);
  // Reference reflectance of eta 0.37 + 2.82i at 60 degrees (complex Fresnel equations in double precision).
  EXPECT_NEAR(b[0].weight.r, 0.8438830f, 2e-6f);
  EXPECT_NEAR(b[0].weight.g, 0.86f * 0.8438830f, 2e-6f);
  EXPECT_NEAR(b[0].weight.b, 0.57f * 0.8438830f, 2e-6f);
}

TEST(Material, DeltaProbabilityAndFlags) {
  Material none;
  EXPECT_EQ(none.flags(), kLobeNone);
  EXPECT_FALSE(none.sample(direction_at(0.5), 0.5f, {0.5f, 0.5f}));

  const Material mirror = delta_material(Mirror{Rgb(0.5f)});
  EXPECT_EQ(mirror.delta_probability(direction_at(0.5)), 1.0f);
  EXPECT_EQ(mirror.flags(), kLobeReflection | kLobeSpecular);

  const Material lambert = surface_material(Lambert{Rgb(0.5f)});
  EXPECT_EQ(lambert.delta_probability(direction_at(0.5)), 0.0f);

  Material both = surface_material(Lambert{Rgb(0.6f)});
  both.delta = Mirror{Rgb(0.2f)};
  EXPECT_NEAR(both.delta_probability(direction_at(0.5)), 0.2f / 0.8f, 1e-6f);
  EXPECT_EQ(both.flags(), kLobeReflection | kLobeDiffuse | kLobeSpecular);

  Material glass = surface_material(Phong{Rgb(0), Rgb(0.3f), 10.0f, PhongVariant::ModifiedNormalized});
  glass.delta = Dielectric{1.5f};
  EXPECT_EQ(glass.flags(), kLobeReflection | kLobeTransmission | kLobeGlossy | kLobeSpecular);
  EXPECT_NEAR(glass.delta_probability(direction_at(0.5)), 1.0f / 1.3f, 1e-6f);
}

TEST(Material, MixtureSamplesDeltaAtItsProbabilityAndScalesPdfs) {
  Material m = surface_material(Phong{Rgb(0.3f), Rgb(0.4f), 10.0f, PhongVariant::ModifiedNormalized});
  m.delta = Conductor{Rgb(0.8f), 0.37f, 2.82f};
  const Vec3f wo = direction_at(0.4, 0.9);
  const float pd = m.delta_probability(wo);
  ASSERT_GT(pd, 0.0f);
  ASSERT_LT(pd, 1.0f);
  std::vector<uint64_t> counts(2, 0);
  Rng rng(5, 6);
  const Phong& ph = std::get<Phong>(m.surface);
  for (int i = 0; i < 50000; ++i) {
    const auto s = m.sample(wo, rng.next_float(), rng.next_2d());
    if (!s) continue;
    if (s->is_specular()) {
      ++counts[1];
      ASSERT_FLOAT_EQ(s->pdf, pd);
    } else {
      ++counts[0];
      ASSERT_NEAR(s->pdf, (1 - pd) * ph.pdf(wo, s->wi), 1e-5f * s->pdf);
    }
  }
  // Surface samples can fail (lobe below the horizon); compare the delta share against its probability among
  // all draws, with the failures folded into the surface entry's expectation.
  const uint64_t drawn = 50000;
  std::vector<uint64_t> obs = {drawn - counts[1], counts[1]};
  const double probs[] = {1.0 - pd, pd};
  const Chi2Result r = chi2_discrete(obs, probs);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Material, SampleDeltaMatchesBranches) {
  const Material glass = delta_material(Dielectric{1.5f});
  const Vec3f wo = direction_at(0.6, 0.3);
  DeltaBranch b[2];
  ASSERT_EQ(glass.delta_branches(wo, b), 2);
  const auto r = glass.sample_delta(wo, 0.0f, {0.5f, 0.5f});
  const auto t = glass.sample_delta(wo, kOneMinusEpsilon, {0.5f, 0.5f});
  ASSERT_TRUE(r && t);
  EXPECT_EQ(r->wi, b[0].wi);
  EXPECT_FALSE(b[0].transmission);
  EXPECT_EQ(t->wi, b[1].wi);
  EXPECT_TRUE(b[1].transmission);
  EXPECT_NEAR(r->f.r * std::abs(r->wi.z), b[0].weight.r, 1e-6f);
  EXPECT_NEAR(t->f.r * std::abs(t->wi.z), b[1].weight.r, 1e-6f);
  EXPECT_FALSE(Material{}.sample_delta(wo, 0.5f, {0.5f, 0.5f}));
}

TEST(Roughness, PerturbationIsUniformInTheSquareAroundTheMirrorDirection) {
  Material m = delta_material(Mirror{Rgb(1.0f)});
  m.roughness = 0.3f;
  const Vec3f wo = direction_at(0.9, 0.6);
  const Vec3f r = reflect_z(wo);
  Vec3f a, b;
  coordinate_system(r, a, b);
  constexpr int kGrid = 5;
  std::vector<uint64_t> counts(kGrid * kGrid, 0);
  Rng rng(13, 14);
  for (int i = 0; i < 100000; ++i) {
    const auto s = m.sample(wo, rng.next_float(), rng.next_2d());
    ASSERT_TRUE(s);  // near-normal incidence: no perturbed ray can cross the surface
    ASSERT_TRUE(s->is_specular());
    // Undo the normalisation: the direction is parallel to r + roughness (xi1 a + xi2 b).
    const Vec3f q = s->wi / dot(s->wi, r);
    const float xi1 = dot(q, a) / m.roughness, xi2 = dot(q, b) / m.roughness;
    ASSERT_LE(std::abs(xi1), 0.5f + 1e-4f);
    ASSERT_LE(std::abs(xi2), 0.5f + 1e-4f);
    const int gx = std::clamp(int((xi1 + 0.5f) * kGrid), 0, kGrid - 1);
    const int gy = std::clamp(int((xi2 + 0.5f) * kGrid), 0, kGrid - 1);
    ++counts[size_t(gy * kGrid + gx)];
    EXPECT_NEAR(s->f.r * s->wi.z / s->pdf, 1.0f, 1e-5f);
  }
  const std::vector<double> probs(kGrid * kGrid, 1.0 / (kGrid * kGrid));
  const Chi2Result res = chi2_discrete(counts, probs);
  EXPECT_TRUE(res.passed) << res.message;
}

TEST(Roughness, PerturbedRaysBelowTheSurfaceAreDropped) {
  Material m = delta_material(Mirror{Rgb(1.0f)});
  m.roughness = 0.8f;
  const Vec3f wo = direction_at(0.05, 0.0);
  Rng rng(15, 16);
  int dropped = 0;
  for (int i = 0; i < 10000; ++i) {
    const auto s = m.sample(wo, rng.next_float(), rng.next_2d());
    if (!s) {
      ++dropped;
      continue;
    }
    ASSERT_GT(s->wi.z, 0.0f);
  }
  EXPECT_GT(dropped, 1000);  // about half the square lies below the horizon at grazing incidence
  EXPECT_LT(dropped, 9000);
}

TEST(Material, TransmittanceIsBeerLambert) {
  Material m = delta_material(Dielectric{1.5f});
  m.absorption = Rgb(0.1f, 0.2f, 0.0f);
  const Rgb t = m.transmittance(3.0f);
  EXPECT_NEAR(t.r, std::exp(-0.3f), 1e-6f);
  EXPECT_NEAR(t.g, std::exp(-0.6f), 1e-6f);
  EXPECT_EQ(t.b, 1.0f);
}

}  // namespace
}  // namespace kiln::test
