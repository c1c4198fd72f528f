// The Light variant's dispatch (sample_li / pdf_li / emitted / power / is_delta) for every light type, and the
// LightSelector's power-proportional and uniform choices.
#include <gtest/gtest.h>

#include <vector>

#include "light_test_util.h"
#include "lights/light.h"
#include "lights/light_selector.h"
#include "support/chi2.h"

namespace kiln {
namespace {

std::vector<Light> one_of_each() {
  std::vector<Light> lights;
  lights.emplace_back(PointLight({0, 0, 3}, Rgb(5.0f)));
  lights.emplace_back(SpotLight({0, 0, 3}, {0, 0, -1}, Rgb(5.0f), 120.0f, 60.0f));
  lights.emplace_back(DirectionalLight({0, 0, -1}, Rgb(1.0f), 10.0f));
  lights.emplace_back(AreaLight::square({0, 0, 3}, {0, 0, -1}, 1.0f, Rgb(2.0f)));
  const std::vector<Vec3f> p{{-1, -1, 3}, {1, -1, 3}, {-1, 1, 3}};
  const std::vector<uint32_t> idx{0, 2, 1};  // wound to face -z, towards the query points
  lights.emplace_back(MeshLight(p, idx, Rgb(2.0f)));
  lights.emplace_back(SphereLight({0, 0, 0}, 1.0f, Transform::translate({0.5f, 0, 3}) * Transform::scale({1, 0.5f, 0.8f}),
                                  Rgb(2.0f)));
  return lights;
}

TEST(Light, DispatchAndPdfConsistencyForEveryType) {
  const std::vector<Light> lights = one_of_each();
  const std::vector<bool> delta{true, true, true, true, false, false};
  Rng rng(12, 34);
  for (size_t i = 0; i < lights.size(); ++i) {
    EXPECT_EQ(is_delta(lights[i]), delta[i]) << "light " << i;
    EXPECT_GT(power(lights[i]), 0.0f) << "light " << i;
    int produced = 0;
    for (int k = 0; k < 500; ++k) {
      const LightQuery q{{rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float()}, {0, 0, 1}};
      const auto s = sample_li(lights[i], q, rng.next_2d());
      if (!s) continue;
      ++produced;
      ASSERT_TRUE(s->li.is_finite() && is_finite(s->wi) && std::isfinite(s->pdf)) << "light " << i;
      EXPECT_NEAR(length(s->wi), 1.0f, 1e-5f);
      EXPECT_EQ(s->delta, delta[i]) << "light " << i;
      const float pdf = pdf_li(lights[i], q, s->p_light, s->n_light, 0);
      if (std::holds_alternative<PointLight>(lights[i]) || std::holds_alternative<SpotLight>(lights[i]) ||
          std::holds_alternative<DirectionalLight>(lights[i])) {
        EXPECT_EQ(s->pdf, 1.0f);
        EXPECT_EQ(pdf, 0.0f);
      } else {
        EXPECT_NEAR(pdf, s->pdf, 1e-3f * s->pdf) << "light " << i;
      }
      // Hittable lights report their radiance back towards q from the sampled point.
      if (!delta[i]) {
        EXPECT_EQ(emitted(lights[i], s->n_light, -s->wi), s->li) << "light " << i;
      }
    }
    EXPECT_GT(produced, 400) << "light " << i;
  }
}

TEST(LightSelector, PowerProportionalChoiceFollowsPower) {
  std::vector<Light> lights = one_of_each();
  lights.emplace_back(PointLight({0, 0, 0}, Rgb(0.0f)));  // dark: never chosen
  const LightSelector sel(lights, LightSelection::PowerProportional);
  ASSERT_FALSE(sel.empty());
  double total = 0;
  for (const Light& l : lights) total += power(l);
  std::vector<double> expected;
  for (size_t i = 0; i < lights.size(); ++i) {
    expected.push_back(power(lights[i]) / total);
    EXPECT_NEAR(sel.pmf(i), expected[i], 1e-6) << i;
  }
  EXPECT_EQ(sel.pmf(lights.size() - 1), 0.0f);
  std::vector<uint64_t> counts(lights.size(), 0);
  Rng rng(3, 3);
  for (int k = 0; k < 100000; ++k) {
    float pmf = 0;
    const size_t i = sel.sample(rng.next_float(), &pmf);
    ASSERT_LT(i, lights.size());
    EXPECT_EQ(pmf, sel.pmf(i));
    ++counts[i];
  }
  const auto r = test::chi2_discrete(counts, expected, 0.01);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(LightSelector, UniformSkipsDarkLights) {
  std::vector<Light> lights = one_of_each();
  lights.insert(lights.begin() + 2, PointLight({0, 0, 0}, Rgb(0.0f)));
  const LightSelector sel(lights, LightSelection::Uniform);
  for (size_t i = 0; i < lights.size(); ++i) EXPECT_FLOAT_EQ(sel.pmf(i), i == 2 ? 0.0f : 1.0f / 6.0f) << i;
  for (int k = 0; k < 1000; ++k) EXPECT_NE(sel.sample((k + 0.5f) / 1000.0f, nullptr), 2u);
}

TEST(LightSelector, EmptyWhenNothingEmits) {
  EXPECT_TRUE(LightSelector().empty());
  const std::vector<Light> none;
  EXPECT_TRUE(LightSelector(none, LightSelection::PowerProportional).empty());
  const std::vector<Light> dark{PointLight({0, 0, 0}, Rgb(0.0f))};
  EXPECT_TRUE(LightSelector(dark, LightSelection::Uniform).empty());
}

}  // namespace
}  // namespace kiln
