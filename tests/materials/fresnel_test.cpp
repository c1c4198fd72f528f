// Fresnel equations and Snell refraction against closed forms, an independent conductor formulation and
// literal reference values.
#include "materials/fresnel.h"

#include <gtest/gtest.h>

#include "brdf_test_util.h"

namespace kiln::test {
namespace {

// pbrt-v3's real-arithmetic conductor Fresnel (a^2 + b^2 form), an independent derivation from the complex one.
double conductor_reference(double c, double eta, double k) {
  const double c2 = c * c, s2 = 1.0 - c2, eta2 = eta * eta, k2 = k * k;
  const double t0 = eta2 - k2 - s2;
  const double a2b2 = std::sqrt(t0 * t0 + 4.0 * eta2 * k2);
  const double t1 = a2b2 + c2;
  const double a = std::sqrt(0.5 * (a2b2 + t0));
  const double t2 = 2.0 * c * a;
  const double rs = (t1 - t2) / (t1 + t2);
  const double t3 = c2 * a2b2 + s2 * s2;
  const double t4 = t2 * s2;
  const double rp = rs * (t3 - t4) / (t3 + t4);
  return 0.5 * (rp + rs);
}

TEST(Fresnel, DielectricNormalIncidenceIsR0) {
  for (float eta : {1.0001f, 1.33f, 1.5f, 2.0f, 10.0f, 0.37f})
    EXPECT_NEAR(fresnel_dielectric(1.0f, eta), sqr((eta - 1.0f) / (eta + 1.0f)), 1e-6f) << eta;
  EXPECT_FLOAT_EQ(fresnel_dielectric(1.0f, 1.0f), 0.0f);
}

TEST(Fresnel, DielectricLiteralValues) {
  // Glass (eta 1.5) at 60 degrees; computed from the Fresnel equations in double precision.
  EXPECT_NEAR(fresnel_dielectric(0.5f, 1.5f), 0.0891867, 1e-6);
  // Grazing incidence reflects everything.
  EXPECT_NEAR(fresnel_dielectric(1e-6f, 1.5f), 1.0f, 1e-4f);
}

TEST(Fresnel, DielectricIsTheSameFromBothSides) {
  // R(theta_i) outside equals R(theta_t) inside (Stokes relations).
  for (float eta : {1.2f, 1.5f, 2.4f}) {
    for (float ci : {0.05f, 0.3f, 0.7f, 0.99f}) {
      const float sin_t = std::sqrt(1.0f - ci * ci) / eta;
      const float ct = std::sqrt(1.0f - sin_t * sin_t);
      EXPECT_NEAR(fresnel_dielectric(ci, eta), fresnel_dielectric(-ct, eta), 2e-5f) << eta << " " << ci;
    }
  }
}

TEST(Fresnel, TotalInternalReflectionBeyondCriticalAngle) {
  const float eta = 1.5f;
  const float cos_critical = std::sqrt(1.0f - 1.0f / (eta * eta));
  EXPECT_EQ(fresnel_dielectric(-(cos_critical - 1e-3f), eta), 1.0f);
  EXPECT_LT(fresnel_dielectric(-(cos_critical + 1e-3f), eta), 1.0f);
  EXPECT_FALSE(refract(Vec3f(0.0f, std::sqrt(1.0f - sqr(cos_critical - 1e-3f)), -(cos_critical - 1e-3f)), eta));
}

TEST(Fresnel, ConductorMatchesReferenceValues) {
  // Gold-like (eta 0.37, kappa 2.82, the course's conductor); literal values from the complex Fresnel
  // equations evaluated in double precision.
  EXPECT_NEAR(fresnel_conductor(1.0f, 0.37f, 2.82f), 0.8494298, 2e-6);
  EXPECT_NEAR(fresnel_conductor(0.5f, 0.37f, 2.82f), 0.8438830, 2e-6);
  EXPECT_NEAR(fresnel_conductor(0.1f, 0.37f, 2.82f), 0.9249612, 2e-6);
  // Normal incidence closed form.
  EXPECT_NEAR(fresnel_conductor(1.0f, 0.37f, 2.82f), fresnel_r0(0.37f, 2.82f), 1e-6f);
}

TEST(Fresnel, ConductorMatchesIndependentFormulation) {
  for (float eta : {0.2f, 0.37f, 1.0f, 1.5f, 3.0f})
    for (float k : {0.0f, 0.5f, 2.82f, 8.0f})
      for (float c : {1.0f, 0.8f, 0.5f, 0.2f, 0.02f}) {
        if (k == 0.0f && eta < 1.0f) continue;  // the a^2+b^2 form needs a lossy or denser medium
        EXPECT_NEAR(fresnel_conductor(c, eta, k), conductor_reference(c, eta, k), 2e-5)
            << "eta " << eta << " kappa " << k << " cos " << c;
      }
}

TEST(Fresnel, ConductorWithoutAbsorptionIsDielectric) {
  for (float c : {1.0f, 0.6f, 0.2f}) EXPECT_NEAR(fresnel_conductor(c, 1.5f, 0.0f), fresnel_dielectric(c, 1.5f), 1e-5f);
}

TEST(Fresnel, SchlickEndpoints) {
  EXPECT_FLOAT_EQ(fresnel_schlick(1.0f, 0.04f), 0.04f);
  EXPECT_FLOAT_EQ(fresnel_schlick(0.0f, 0.04f), 1.0f);
  EXPECT_NEAR(fresnel_schlick(0.5f, 0.04f), 0.04f + 0.96f / 32.0f, 1e-7f);
  EXPECT_NEAR(fresnel_r0(0.37f), sqr(0.63f / 1.37f), 1e-7f);
}

TEST(Fresnel, RefractionObeysSnell) {
  for (float eta : {1.0001f, 1.5f, 10.0f})
    for (float c : {1.0f, 0.7f, 0.1f, 1e-4f}) {
      const Vec3f wo = direction_at(c, 1.1);
      const auto t = refract(wo, eta);
      ASSERT_TRUE(t) << eta << " " << c;
      EXPECT_NEAR(length(t->wt), 1.0f, 1e-5f);
      EXPECT_LT(t->wt.z, 0.0f);
      EXPECT_FLOAT_EQ(t->etap, eta);
      // eta_o sin(theta_o) = eta_t sin(theta_t), and wt lies in the plane of incidence, opposite to wo.
      EXPECT_NEAR(std::sqrt(sin2_theta(wo)), eta * std::sqrt(sin2_theta(t->wt)), 2e-5f);
      EXPECT_NEAR(wo.x * t->wt.y - wo.y * t->wt.x, 0.0f, 1e-6f);
      EXPECT_LE(wo.x * t->wt.x + wo.y * t->wt.y, 0.0f);
      // Refracting back from inside returns to wo (away from grazing, where the reverse ray sits at the critical
      // angle and rounding may call it total internal reflection).
      if (c < 0.1f) continue;
      const auto back = refract(t->wt, eta);
      ASSERT_TRUE(back) << eta << " " << c;
      EXPECT_NEAR(back->wt.x, wo.x, 1e-4f);
      EXPECT_NEAR(back->wt.y, wo.y, 1e-4f);
      EXPECT_NEAR(back->wt.z, wo.z, 1e-4f);
      EXPECT_FLOAT_EQ(back->etap, 1.0f / eta);
    }
}

}  // namespace
}  // namespace kiln::test
