// Extreme parameters and directions: exponents 0 ... 1e5, refractive indices 1.0001 ... 10 (and < 1), grazing
// angles down to cos = 1e-6, directions exactly in the surface plane and below it. Nothing may return NaN,
// Inf or a negative value.
#include <gtest/gtest.h>

#include <vector>

#include "brdf_test_util.h"
#include "core/sampling.h"

namespace kiln::test {
namespace {

std::vector<std::pair<std::string, Material>> extreme_materials() {
  std::vector<std::pair<std::string, Material>> out;
  const Rgb kd(0.4f), ks(0.6f);
  for (float p : {0.0f, 1.0f, 7.5f, 1000.0f, 1e5f}) {
    const std::string ps = " p=" + std::to_string(p);
    for (PhongVariant v : {PhongVariant::Original, PhongVariant::Modified, PhongVariant::ModifiedNormalized}) {
      out.push_back({"Phong " + variant_name(v) + ps, surface_material(Phong{kd, ks, p, v})});
      out.push_back({"Phong lobe only " + variant_name(v) + ps, surface_material(Phong{Rgb(0), ks, p, v})});
      out.push_back({"Blinn " + variant_name(v) + ps, surface_material(BlinnPhong{kd, ks, p, v})});
      out.push_back({"Blinn lobe only " + variant_name(v) + ps, surface_material(BlinnPhong{Rgb(0), ks, p, v})});
    }
    for (float eta : {1.0001f, 1.5f, 10.0f, 0.37f})
      for (float kappa : {0.0f, 2.82f})
        for (bool kf : {false, true})
          out.push_back({"TS" + ps + " eta=" + std::to_string(eta) + " kappa=" + std::to_string(kappa),
                         surface_material(TorranceSparrow{kd, ks, p, eta, kappa, kf})});
  }
  out.push_back({"Lambert", surface_material(Lambert{Rgb(1)})});
  for (float eta : {1.0001f, 1.5f, 10.0f, 1.0f, 0.5f})
    for (float roughness : {0.0f, 0.5f}) {
      Material glass = surface_material(Phong{Rgb(0), Rgb(0.3f), 200.0f, PhongVariant::ModifiedNormalized});
      glass.delta = Dielectric{eta};
      glass.roughness = roughness;
      out.push_back({"Glass eta=" + std::to_string(eta) + " r=" + std::to_string(roughness), glass});
      Material bare;
      bare.delta = Dielectric{eta};
      bare.roughness = roughness;
      out.push_back({"BareGlass eta=" + std::to_string(eta) + " r=" + std::to_string(roughness), bare});
      Material metal = surface_material(BlinnPhong{Rgb(0.1f), Rgb(0.2f), 1e5f, PhongVariant::Original});
      metal.delta = Conductor{Rgb(1), eta, 2.82f};
      metal.roughness = roughness;
      out.push_back({"Metal eta=" + std::to_string(eta) + " r=" + std::to_string(roughness), metal});
    }
  Material mirror;
  mirror.delta = Mirror{Rgb(0.9f)};
  mirror.roughness = 2.0f;
  out.push_back({"RoughMirror", mirror});
  return out;
}

std::vector<Vec3f> extreme_directions() {
  std::vector<Vec3f> d;
  for (double c : {1.0, 0.999999, 0.5, 1e-3, 1e-6, 0.0, -1e-6, -0.5, -1.0})
    for (double phi : {0.0, 1.3, 4.0}) d.push_back(direction_at(c, phi));
  return d;
}

bool valid(Rgb c) { return c.is_finite() && !c.has_negative(); }
bool valid(float x) { return std::isfinite(x) && x >= 0.0f; }

TEST(Robustness, NoNanInfOrNegativeAnywhere) {
  const auto materials = extreme_materials();
  const auto dirs = extreme_directions();
  Rng rng(99, 100);
  for (const auto& [name, m] : materials) {
    for (const Vec3f& wo : dirs) {
      SCOPED_TRACE(name + " wo.z=" + std::to_string(wo.z));
      ASSERT_TRUE(valid(m.delta_probability(wo)));
      ASSERT_LE(m.delta_probability(wo), 1.0f);
      // eval / pdf on special directions: the extreme set, the mirror direction (peak of every lobe) and
      // random ones.
      std::vector<Vec3f> wis = dirs;
      wis.push_back(Vec3f(-wo.x, -wo.y, wo.z));
      for (int i = 0; i < 30; ++i) wis.push_back(sample_uniform_sphere(rng.next_2d()));
      for (const Vec3f& wi : wis) {
        ASSERT_TRUE(valid(m.eval(wo, wi))) << "wi " << wi.x << " " << wi.y << " " << wi.z;
        ASSERT_TRUE(valid(m.pdf(wo, wi))) << "wi " << wi.x << " " << wi.y << " " << wi.z;
      }
      for (int i = 0; i < 200; ++i) {
        const float uc = i == 0 ? 0.0f : (i == 1 ? kOneMinusEpsilon : rng.next_float());
        const Vec2f u = i < 2 ? Vec2f(float(i) * kOneMinusEpsilon, 0.0f) : rng.next_2d();
        const auto s = m.sample(wo, uc, u);
        if (!s) continue;
        ASSERT_TRUE(valid(s->f));
        ASSERT_TRUE(std::isfinite(s->pdf) && s->pdf > 0.0f);
        ASSERT_TRUE(is_finite(s->wi));
        ASSERT_NEAR(length(s->wi), 1.0f, 1e-4f);
        ASSERT_TRUE(std::isfinite(s->eta) && s->eta > 0.0f);
        const Rgb w = s->f * (std::abs(s->wi.z) / s->pdf);
        ASSERT_TRUE(valid(w)) << "path weight";
      }
      DeltaBranch b[2];
      const int n = m.delta_branches(wo, b);
      for (int i = 0; i < n; ++i) {
        ASSERT_TRUE(valid(b[i].weight));
        ASSERT_TRUE(is_finite(b[i].wi));
        ASSERT_NEAR(length(b[i].wi), 1.0f, 1e-4f);
      }
    }
  }
}

TEST(Robustness, SharpLobesKeepTheirPeak) {
  // Exponent 1e5: the lobe is ~0.2 degrees wide; sampling must still land around the mirror direction and the
  // pdf there must be finite and large rather than rounded to 0 or Inf.
  const Material m = surface_material(Phong{Rgb(0), Rgb(1), 1e5f, PhongVariant::ModifiedNormalized});
  const Vec3f wo = direction_at(0.5, 0.0);
  const Vec3f r(-wo.x, -wo.y, wo.z);
  EXPECT_NEAR(m.pdf(wo, r), (1e5 + 1) / (2 * 3.14159265358979), 2.0);
  Rng rng(1, 1);
  for (int i = 0; i < 1000; ++i) {
    const auto s = m.sample(wo, rng.next_float(), rng.next_2d());
    ASSERT_TRUE(s);
    EXPECT_GT(dot(s->wi, r), 0.9995f);
    EXPECT_GT(s->pdf, 0.0f);
  }
}

}  // namespace
}  // namespace kiln::test
