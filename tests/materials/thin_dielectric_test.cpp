// ThinDielectric (pbrt-v4 "thindielectric"): an infinitely thin slab.
//  * Closed form: its reflectance R(theta) is the sum over the light's internal bounces, computed here explicitly
//    (r, then t r t, t r^3 t, ... with r the Fresnel reflectance in double precision) and compared with the BxDF's
//    R, at incidences down to grazing, for slabs denser and less dense than their surroundings;
//  * energy: R + T = 1 exactly; transmission leaves straight through (wi = -wo) with no change of medium;
//  * sampling: reflection and transmission are chosen with probabilities R and T (chi-square), from either side,
//    each sample carrying the path weight 1.
#include <gtest/gtest.h>

#include "brdf_test_util.h"
#include "support/chi2.h"

namespace kiln::test {
namespace {

// The slab's reflectance by following the light inside: each internal round trip reflects twice with r.
double summed_bounces(double cos_i, double eta) {
  const double r = fresnel_dielectric_ref(cos_i, 1, eta), t = 1 - r;
  if (r >= 1) return 1;
  double R = r, inside = t;  // energy travelling inside towards the far face
  for (int bounce = 0; bounce < 10000 && inside > 1e-17; ++bounce) {
    const double back = inside * r;  // reflected at the far face, heading back
    R += back * t;                   // leaves through the near face
    inside = back * r;               // reflected again at the near face
  }
  return R;
}

constexpr float kEtas[] = {1.5f, 1.33f, 2.4f, 0.75f};
constexpr float kCosines[] = {1.0f, 0.8f, 0.5f, 0.2f, 0.05f, 0.005f};

TEST(ThinDielectric, ReflectanceIsTheSumOverInternalBounces) {
  for (float eta : kEtas)
    for (float c : kCosines) {
      const ThinDielectric slab{eta};
      const double expected = summed_bounces(c, eta);
      EXPECT_NEAR(slab.reflectance(c), expected, 2e-6 + 1e-5 * expected) << "eta " << eta << " cos " << c;
      EXPECT_EQ(slab.reflectance(-c), slab.reflectance(c));  // the same from either side
    }
  // eta = 1: no slab at all.
  EXPECT_EQ(ThinDielectric{1.0f}.reflectance(0.3f), 0.0f);
}

TEST(ThinDielectric, BranchesConserveEnergyAndPassStraightThrough) {
  for (float eta : kEtas)
    for (float c : kCosines)
      for (float side : {1.0f, -1.0f}) {
        const Vec3f wo = direction_at(side * c, 0.4);
        SpecularBranch b[2];
        const int n = ThinDielectric{eta}.branches(wo, b);
        ASSERT_GE(n, 1);
        float total = 0.0f;
        for (int i = 0; i < n; ++i) {
          total += b[i].probability;
          EXPECT_EQ(b[i].weight, Rgb(b[i].probability));
          EXPECT_EQ(b[i].etap, 1.0f);
          if (b[i].transmission) {
            EXPECT_EQ(b[i].wi, -wo);
          } else {
            EXPECT_EQ(b[i].wi, reflect_z(wo));
          }
        }
        EXPECT_NEAR(total, 1.0f, 1e-6f) << "eta " << eta << " cos " << c;
      }
}

TEST(ThinDielectric, SamplingChoosesReflectionWithProbabilityR) {
  const int num_tests = int(std::size(kEtas) * 3);
  for (float eta : kEtas)
    for (float c : {0.9f, 0.3f, -0.1f}) {
      Material m;
      m.delta = ThinDielectric{eta};
      const Vec3f wo = direction_at(c, 0.2);
      Rng rng(11, uint64_t(eta * 100 + c * 10));
      uint64_t counts[2] = {0, 0};
      for (int i = 0; i < 200000; ++i) {
        const float uc = rng.next_float();
        const auto s = m.sample(wo, uc, rng.next_2d());
        ASSERT_TRUE(s);
        ASSERT_TRUE(s->is_specular());
        ASSERT_NEAR(s->f.g * std::abs(s->wi.z) / s->pdf, 1.0f, 1e-5f);  // the path weight
        ++counts[s->is_transmission() ? 1 : 0];
      }
      const double R = summed_bounces(std::abs(c), eta);
      if (R == 1.0) {  // total reflection (a slab less dense than its surroundings, beyond the critical angle)
        EXPECT_EQ(counts[1], 0u) << "eta " << eta << " cos " << c;
        continue;
      }
      const double probs[2] = {R, 1 - R};
      const Chi2Result r = chi2_discrete(counts, probs, 0.01, num_tests);
      EXPECT_TRUE(r.passed) << "eta " << eta << " cos " << c << "\n" << r.message;
    }
}

TEST(ThinDielectric, IsTwoSidedAndChangesNoMedium) {
  Material m;
  m.delta = ThinDielectric{1.5f};
  EXPECT_FALSE(m.oriented());
  EXPECT_TRUE(m.has_delta());
  EXPECT_EQ(m.describe(), "thin-dielectric");
}

}  // namespace
}  // namespace kiln::test
