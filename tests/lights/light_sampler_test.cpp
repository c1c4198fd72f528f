// The light samplers (lights/light_sampler.h) and the light hierarchy under the bvh one (lights/light_tree.h):
// at fixed shading points the lights chosen follow the probabilities pmf() reports (chi-square), those sum to 1,
// sample() reports the same probability pmf() gives, a light that can light a point is never given probability 0,
// one light is chosen with probability 1, and the tree stays within its depth on adversarial layouts.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <ostream>
#include <vector>

#include "lights/light_sampler.h"
#include "lights/light_tree.h"
#include "support/chi2.h"

namespace kiln {

// gtest prints a failed comparison of samplers by name.
void PrintTo(LightSamplerKind kind, std::ostream* os) { *os << light_sampler_name(kind); }

namespace {

// A quad of two triangles at height y facing down (-y), centred at (x, z), side s.
MeshLight ceiling_quad(float x, float z, float y, float s, Rgb radiance, bool two_sided = false) {
  const float h = 0.5f * s;
  const std::vector<Vec3f> p{{x - h, y, z - h}, {x + h, y, z - h}, {x + h, y, z + h}, {x - h, y, z + h}};
  const std::vector<uint32_t> down{0, 1, 2, 0, 2, 3};  // (v1-v0)x(v2-v0) = -y: faces the floor
  return MeshLight(p, down, radiance, two_sided);
}

// Every kind of light with a position, in a 10 x 10 room with its lamps at y = 10, plus two at infinity.
std::vector<Light> many_kinds() {
  std::vector<Light> lights;
  Rng rng(5, 9);
  for (int i = 0; i < 12; ++i) {
    const float power = std::pow(10.0f, 2.0f * rng.next_float());  // 100x spread, as the race's room
    lights.emplace_back(ceiling_quad(1.0f + 8.0f * rng.next_float(), 1.0f + 8.0f * rng.next_float(), 10.0f, 0.5f,
                                     Rgb(power * rng.next_float(), power * rng.next_float(), power)));
  }
  lights.emplace_back(ceiling_quad(5.0f, 5.0f, 6.0f, 1.0f, Rgb(3.0f), true));  // two-sided, mid-air
  lights.emplace_back(PointLight({2, 4, 2}, Rgb(20.0f)));
  lights.emplace_back(SpotLight({8, 9, 8}, {0, -1, 0}, Rgb(50.0f), 60.0f, 20.0f));
  // A falloff ring wider than a hemisphere: it still lights points above the spot.
  lights.emplace_back(SpotLight({3, 2, 7}, {0, -1, 0}, Rgb(10.0f), 300.0f, 30.0f));
  lights.emplace_back(SphereLight({0, 0, 0}, 0.5f, Transform::translate({7, 3, 3}), Rgb(4.0f)));
  lights.emplace_back(AreaLight::square({0.5f, 5, 5}, {1, 0, 0}, 1.0f, Rgb(2.0f)));
  lights.emplace_back(DirectionalLight({0, -1, 0}, Rgb(1.0f), 20.0f));
  lights.emplace_back(InfiniteLight(Rgb(0.2f), 20.0f));
  return lights;
}

// Every part the sampler can choose, with pmf(q, .) for each.
struct Part {
  uint32_t light, part;
};
std::vector<Part> parts_of(const LightSampler& s, const std::vector<Light>& lights) {
  std::vector<Part> parts;
  for (uint32_t i = 0; i < lights.size(); ++i) {
    const auto* mesh = std::get_if<MeshLight>(&lights[i]);
    if (mesh && s.part(i, 0) != kWholeLight) {
      for (uint32_t t = 0; t < mesh->triangle_count(); ++t) parts.push_back({i, t});
    } else {
      parts.push_back({i, kWholeLight});
    }
  }
  return parts;
}

struct Point {
  const char* name;
  LightQuery q;
};
// On a lamp, above the lamps, on the floor facing up and facing away (down), between lamps, without a normal.
const Point kPoints[] = {
    {"on a lamp", {{5.0f, 6.0f, 5.0f}, {0, -1, 0}}},
    {"above the lamps", {{5.0f, 11.0f, 5.0f}, {0, 1, 0}}},
    {"floor facing up", {{4.0f, 0.0f, 6.0f}, {0, 1, 0}}},
    {"floor facing away", {{4.0f, 0.0f, 6.0f}, {0, -1, 0}}},
    {"wall", {{0.0f, 5.0f, 2.0f}, {1, 0, 0}}},
    {"no normal", {{6.0f, 8.0f, 3.0f}, {0, 0, 0}}},
};

class LightSamplerKinds : public ::testing::TestWithParam<LightSamplerKind> {};

TEST_P(LightSamplerKinds, ChosenLightsFollowTheReportedPmf) {
  const std::vector<Light> lights = many_kinds();
  const LightSampler sampler(lights, GetParam());
  const std::vector<Part> parts = parts_of(sampler, lights);
  for (const Point& pt : kPoints) {
    std::vector<double> expected;
    double sum = 0.0;
    std::map<std::pair<uint32_t, uint32_t>, size_t> index;
    for (const Part& p : parts) {
      index[{p.light, p.part}] = expected.size();
      expected.push_back(sampler.pmf(pt.q, p.light, p.part));
      sum += expected.back();
    }
    EXPECT_NEAR(sum, 1.0, 1e-5) << pt.name;
    std::vector<uint64_t> counts(parts.size(), 0);
    Rng rng(17, 3);
    constexpr int kSamples = 200000;
    for (int k = 0; k < kSamples; ++k) {
      const auto s = sampler.sample(pt.q, rng.next_float());
      ASSERT_TRUE(s) << pt.name;
      const auto it = index.find({s->light, s->part});
      ASSERT_NE(it, index.end()) << pt.name << ": light " << s->light << " part " << s->part;
      ++counts[it->second];
      ASSERT_NEAR(s->pmf, expected[it->second], 1e-5 * expected[it->second]) << pt.name << ": light " << s->light;
    }
    const auto r = test::chi2_discrete(counts, expected, 0.01, int(std::size(kPoints)) * 3);
    EXPECT_TRUE(r.passed) << pt.name << ": " << r.message;
  }
}

INSTANTIATE_TEST_SUITE_P(All, LightSamplerKinds,
                         ::testing::Values(LightSamplerKind::Power, LightSamplerKind::Uniform, LightSamplerKind::Bvh),
                         [](const auto& p) { return std::string(light_sampler_name(p.param)); });

TEST(LightTree, SplitsMeshLightsAndHoldsEveryPositionedLight) {
  const std::vector<Light> lights = many_kinds();
  const LightSampler sampler(lights, LightSamplerKind::Bvh);
  const LightSamplerStats& st = sampler.stats();
  EXPECT_EQ(st.emitters, 13u * 2u + 5u);  // 13 quads of 2 triangles; point, 2 spots, sphere, area light
  EXPECT_GE(st.nodes, (st.emitters - 1 + 2) / 3);  // four children per node
  EXPECT_LT(st.nodes, st.emitters);
  EXPECT_EQ(st.infinite_lights, 2u);
  EXPECT_EQ(sampler.part(0, 1), 1u);
  EXPECT_EQ(sampler.part(13, 0), kWholeLight);
}

// Conservative importance: wherever a light sends anything to a point, the hierarchy gives it a positive
// probability (a light it never chose there would be missing from NEE-only estimates, and from delta lights'
// light altogether).
TEST(LightTree, NeverGivesZeroToALightThatReachesThePoint) {
  const std::vector<Light> lights = many_kinds();
  const LightSampler sampler(lights, LightSamplerKind::Bvh);
  const std::vector<Part> parts = parts_of(sampler, lights);
  Rng rng(99, 1);
  int reaching = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3f p{12.0f * rng.next_float() - 1.0f, 12.0f * rng.next_float() - 1.0f, 12.0f * rng.next_float() - 1.0f};
    const Vec3f n = k % 4 == 0 ? Vec3f(0.0f) : normalize(Vec3f(rng.next_float() - 0.5f, rng.next_float() - 0.5f,
                                                               rng.next_float() - 0.5f));
    const LightQuery q{p, n};
    for (const Part& part : parts) {
      const auto s = sample_li(lights[part.light], part.part, q, rng.next_2d());
      if (!s || s->li.is_black() || !(s->pdf > 0.0f)) continue;
      if (n != Vec3f(0.0f) && std::abs(dot(n, s->wi)) <= 0.0f) continue;
      ++reaching;
      ASSERT_GT(sampler.pmf(q, part.light, part.part), 0.0f)
          << "light " << part.light << " part " << part.part << " at (" << p.x << ", " << p.y << ", " << p.z << ")";
    }
  }
  EXPECT_GT(reaching, 40000);
}

// A one-sided lamp cannot light what is behind it: above two lamps facing down, a dimmer point light beside them
// gets all the probability (that is where the hierarchy gains); below them, the nearer lamp gets most of it.
TEST(LightTree, GivesNothingToALampSeenFromBehind) {
  std::vector<Light> lights;
  lights.emplace_back(ceiling_quad(2.0f, 2.0f, 10.0f, 1.0f, Rgb(5.0f)));
  lights.emplace_back(ceiling_quad(8.0f, 8.0f, 10.0f, 1.0f, Rgb(5.0f)));
  lights.emplace_back(PointLight({5.0f, 5.0f, 5.0f}, Rgb(0.1f)));
  const LightSampler sampler(lights, LightSamplerKind::Bvh);
  const LightQuery above{{2.0f, 12.0f, 2.0f}, {0, 1, 0}};
  EXPECT_EQ(sampler.pmf(above, 2, kWholeLight), 1.0f);
  for (uint32_t t = 0; t < 2; ++t) EXPECT_EQ(sampler.pmf(above, 0, t) + sampler.pmf(above, 1, t), 0.0f);
  const LightQuery below{{2.0f, 8.0f, 2.0f}, {0, 1, 0}};
  EXPECT_GT(sampler.pmf(below, 0, 0) + sampler.pmf(below, 0, 1), 0.9f);
}

TEST(LightSampler, OneLightIsChosenWithProbabilityOne) {
  for (const LightSamplerKind kind : {LightSamplerKind::Power, LightSamplerKind::Uniform, LightSamplerKind::Bvh}) {
    const std::vector<Light> lights{SphereLight({0, 0, 0}, 1.0f, Transform::translate({0, 5, 0}), Rgb(2.0f))};
    const LightSampler sampler(lights, kind);
    for (const Point& pt : kPoints) {
      EXPECT_EQ(sampler.pmf(pt.q, 0, kWholeLight), 1.0f) << light_sampler_name(kind) << " " << pt.name;
      for (const float u : {0.0f, 0.37f, kOneMinusEpsilon}) {
        const auto s = sampler.sample(pt.q, u);
        ASSERT_TRUE(s) << light_sampler_name(kind) << " " << pt.name;
        EXPECT_EQ(s->light, 0u);
        EXPECT_EQ(s->pmf, 1.0f);
      }
    }
  }
}

TEST(LightSampler, DefaultIsTheHierarchyOnlyWhenThereIsAChoice) {
  const std::vector<Light> one{ceiling_quad(0, 0, 1, 1, Rgb(1.0f))};
  EXPECT_EQ(default_light_sampler(one), LightSamplerKind::Power);
  std::vector<Light> with_sky = one;
  with_sky.emplace_back(InfiniteLight(Rgb(1.0f), 10.0f));
  EXPECT_EQ(default_light_sampler(with_sky), LightSamplerKind::Power);
  std::vector<Light> two = one;
  two.emplace_back(PointLight({0, 0, 0}, Rgb(1.0f)));
  EXPECT_EQ(default_light_sampler(two), LightSamplerKind::Bvh);
  std::vector<Light> dark = one;
  dark.emplace_back(PointLight({0, 0, 0}, Rgb(0.0f)));
  EXPECT_EQ(default_light_sampler(dark), LightSamplerKind::Power);
  // One large emissive mesh: chosen triangle by triangle.
  std::vector<Vec3f> p;
  std::vector<uint32_t> idx;
  for (uint32_t i = 0; i <= kSplitMeshTriangles; ++i) {
    p.insert(p.end(), {{float(i), 0, 0}, {float(i) + 1, 0, 0}, {float(i), 1, 0}});
    idx.insert(idx.end(), {3 * i, 3 * i + 1, 3 * i + 2});
  }
  const std::vector<Light> mesh{MeshLight(p, idx, Rgb(1.0f))};
  EXPECT_EQ(default_light_sampler(mesh), LightSamplerKind::Bvh);
}

// Pairs of point lights at 16^k along each axis: every bucket split peels off the farthest pair, so the tree is
// about as deep as there are pairs, and trails longer than 32 bits must still lead to their leaves. With a smaller
// depth limit the same layout is split at the median past it, and stays within the limit.
std::vector<EmitterBounds> peeling_layout(std::vector<Light>& lights) {
  std::vector<EmitterBounds> emitters;
  for (int axis = 0; axis < 3; ++axis)
    for (int k = 1; k < 15; ++k)
      for (int j = 0; j < 2; ++j) {
        Vec3f p(0.5f * float(j));
        p[axis] = std::ldexp(1.0f, 4 * k);
        lights.emplace_back(PointLight(p, Rgb(1.0f)));
        append_emitter_bounds(lights.back(), uint32_t(lights.size() - 1), emitters);
      }
  return emitters;
}

void expect_consistent(const LightTree& tree, size_t light_count, const LightQuery& q) {
  double sum = 0.0;
  for (uint32_t i = 0; i < light_count; ++i) sum += tree.pmf(q.p, q.n, i, kWholeLight);
  EXPECT_NEAR(sum, 1.0, 1e-5);
  Rng rng(4, 4);
  for (int k = 0; k < 4000; ++k) {
    const auto s = tree.sample(q.p, q.n, rng.next_float());
    ASSERT_TRUE(s);
    ASSERT_NEAR(s->pmf, tree.pmf(q.p, q.n, s->light, kWholeLight), 1e-5f * s->pmf) << "light " << s->light;
  }
}

TEST(LightTree, TrailsLongerThan32BitsAndTheDepthLimit) {
  std::vector<Light> lights;
  const std::vector<EmitterBounds> emitters = peeling_layout(lights);
  const LightQuery q{{0.5f, 1, 0.25f}, {0, 0, 0}};
  const LightTree deep(emitters, lights.size());
  EXPECT_GT(deep.depth(), 16);  // more than 32 bits of trail
  EXPECT_LE(deep.depth(), kMaxLightTreeDepth);
  expect_consistent(deep, lights.size(), q);
  const LightTree capped(emitters, lights.size(), 5);
  EXPECT_LE(capped.depth(), 5);
  expect_consistent(capped, lights.size(), q);
}

TEST(LightSampler, NamesRoundTrip) {
  for (const LightSamplerKind k : {LightSamplerKind::Power, LightSamplerKind::Uniform, LightSamplerKind::Bvh})
    EXPECT_EQ(parse_light_sampler(light_sampler_name(k)), k);
  EXPECT_FALSE(parse_light_sampler("tree"));
}

}  // namespace
}  // namespace kiln
