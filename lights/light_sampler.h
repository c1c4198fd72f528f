// Which light a next-event-estimation sample goes to, and the probability of that choice for MIS.
//   power    the power-proportional selector (lights/light_selector.h): blind to the shading point; each light
//            whole (a mesh light then picks its triangle by area)
//   uniform  every light with power the same probability
//   bvh      the light hierarchy (lights/light_tree.h): emitters chosen by their importance at the shading point,
//            mesh lights triangle by triangle; lights at infinity (directional, infinite, environment) beside the
//            tree, as pbrt-v4 does: each with probability 1 / (their count + 1), the tree with the rest
// The default (default_light_sampler) is the hierarchy when there is a choice to make among lights with a position,
// the power selector otherwise (one light, or one small mesh light, pays for nothing).
#pragma once
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lights/light_selector.h"
#include "lights/light_tree.h"

namespace kiln {

enum class LightSamplerKind { Power, Uniform, Bvh };

const char* light_sampler_name(LightSamplerKind kind);
// "power", "uniform", "bvh"; nothing for any other name.
std::optional<LightSamplerKind> parse_light_sampler(const std::string& name);

// A mesh light holding more triangles than this is worth choosing triangle by triangle even when it is the only
// light (a small one, such as a quad, is not).
inline constexpr size_t kSplitMeshTriangles = 64;
LightSamplerKind default_light_sampler(std::span<const Light> lights);

// The part of a light a sampler chose (kWholeLight or a triangle of a mesh light) and its probability.
struct SampledLight {
  uint32_t light = 0;
  uint32_t part = kWholeLight;
  float pmf = 0.0f;
};

struct LightSamplerStats {
  LightSamplerKind kind = LightSamplerKind::Power;
  size_t emitters = 0;        // bvh: parts in the tree (lights and mesh triangles with power)
  size_t nodes = 0;           // bvh: 4-wide interior nodes
  int depth = 0;              // bvh: deepest leaf
  size_t infinite_lights = 0; // bvh: lights sampled beside the tree
  size_t bytes = 0;
  double build_seconds = 0;
};

class LightSampler {
 public:
  LightSampler() = default;
  LightSampler(std::span<const Light> lights, LightSamplerKind kind);

  bool empty() const;
  // sample() reads u: there is more than one light to choose from, or the hierarchy walks to one.
  bool chooses() const { return stats_.kind == LightSamplerKind::Bvh || selector_.size() > 1; }
  // The chosen part and its probability for a shading point (q.n may be zero); u in [0, 1). Empty when no light
  // can be chosen.
  std::optional<SampledLight> sample(const LightQuery& q, float u) const {
    if (stats_.kind == LightSamplerKind::Bvh) return sample_bvh(q, u);
    float pmf = selector_.pmf(0);  // one light: no choice to make (u is not drawn)
    const size_t i = chooses() ? selector_.sample(u, &pmf) : 0;
    if (!(pmf > 0.0f)) return std::nullopt;
    return SampledLight{uint32_t(i), kWholeLight, pmf};
  }
  // The part of light `light` that a point on its triangle prim belongs to, as sample() chooses parts.
  uint32_t part(uint32_t light, uint32_t prim) const { return tree_.splits(light) ? prim : kWholeLight; }
  // Probability that sample(q, .) chooses that part of that light.
  float pmf(const LightQuery& q, uint32_t light, uint32_t part) const {
    return stats_.kind == LightSamplerKind::Bvh ? pmf_bvh(q, light, part) : selector_.pmf(light);
  }
  const LightSamplerStats& stats() const { return stats_; }

 private:
  std::optional<SampledLight> sample_bvh(const LightQuery& q, float u) const;
  float pmf_bvh(const LightQuery& q, uint32_t light, uint32_t part) const;

  LightSamplerStats stats_;
  LightSelector selector_;           // power, uniform
  LightTree tree_;                   // bvh
  std::vector<uint32_t> infinite_;   // bvh: lights at infinity
  std::vector<uint8_t> is_infinite_; // bvh: per light
  float p_infinite_ = 0.0f;          // bvh: probability of choosing among infinite_
};

}  // namespace kiln
