#include "lights/light_sampler.h"

#include <chrono>

namespace kiln {

const char* light_sampler_name(LightSamplerKind kind) {
  switch (kind) {
    case LightSamplerKind::Power: return "power";
    case LightSamplerKind::Uniform: return "uniform";
    case LightSamplerKind::Bvh: return "bvh";
  }
  return "?";
}

std::optional<LightSamplerKind> parse_light_sampler(const std::string& name) {
  for (const LightSamplerKind k : {LightSamplerKind::Power, LightSamplerKind::Uniform, LightSamplerKind::Bvh})
    if (name == light_sampler_name(k)) return k;
  return std::nullopt;
}

LightSamplerKind default_light_sampler(std::span<const Light> lights) {
  size_t positioned = 0;
  bool large_mesh = false;
  std::vector<EmitterBounds> scratch;
  for (const Light& l : lights) {
    if (!(power(l) > 0.0f)) continue;
    if (const auto* mesh = std::get_if<MeshLight>(&l)) {
      ++positioned;
      large_mesh |= mesh->triangle_count() > kSplitMeshTriangles;
      continue;
    }
    scratch.clear();
    if (append_emitter_bounds(l, 0, scratch)) ++positioned;
  }
  return positioned >= 2 || large_mesh ? LightSamplerKind::Bvh : LightSamplerKind::Power;
}

LightSampler::LightSampler(std::span<const Light> lights, LightSamplerKind kind) {
  const auto start = std::chrono::steady_clock::now();
  stats_.kind = kind;
  if (kind == LightSamplerKind::Bvh) {
    std::vector<EmitterBounds> emitters;
    is_infinite_.assign(lights.size(), 0);
    for (size_t i = 0; i < lights.size(); ++i) {
      if (append_emitter_bounds(lights[i], uint32_t(i), emitters) || !(power(lights[i]) > 0.0f)) continue;
      infinite_.push_back(uint32_t(i));
      is_infinite_[i] = 1;
    }
    tree_ = LightTree(std::move(emitters), lights.size());
    const size_t groups = infinite_.size() + (tree_.empty() ? 0 : 1);
    p_infinite_ = groups > 0 ? float(infinite_.size()) / float(groups) : 0.0f;
    stats_.emitters = tree_.emitter_count();
    stats_.nodes = tree_.node_count();
    stats_.depth = tree_.depth();
    stats_.infinite_lights = infinite_.size();
    stats_.bytes = tree_.bytes() + infinite_.capacity() * sizeof(uint32_t) + is_infinite_.capacity();
  } else {
    selector_ = LightSelector(lights, kind == LightSamplerKind::Uniform ? LightSelection::Uniform
                                                                        : LightSelection::PowerProportional);
  }
  stats_.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool LightSampler::empty() const {
  return stats_.kind == LightSamplerKind::Bvh ? tree_.empty() && infinite_.empty() : selector_.empty();
}

std::optional<SampledLight> LightSampler::sample_bvh(const LightQuery& q, float u) const {
  if (u < p_infinite_) {
    const size_t n = infinite_.size();
    const size_t i = std::min(size_t(u / p_infinite_ * float(n)), n - 1);
    return SampledLight{infinite_[i], kWholeLight, p_infinite_ / float(n)};
  }
  const float u_tree = std::min((u - p_infinite_) / (1.0f - p_infinite_), kOneMinusEpsilon);
  const auto c = tree_.sample(q.p, q.n, u_tree);
  if (!c) return std::nullopt;
  return SampledLight{c->light, c->part, c->pmf * (1.0f - p_infinite_)};
}

float LightSampler::pmf_bvh(const LightQuery& q, uint32_t light, uint32_t part) const {
  if (light < is_infinite_.size() && is_infinite_[light]) return p_infinite_ / float(infinite_.size());
  return (1.0f - p_infinite_) * tree_.pmf(q.p, q.n, light, part);
}

}  // namespace kiln
