#include "renderer/world/material_mix.h"

#include <bit>

#include "core/error.h"
#include "core/rng.h"

namespace kiln {
namespace {

constexpr uint64_t kMixSalt = 0x6d6978ull;  // "mix"

// Uniform in [0, 1), a hash of the hit and of the mix deciding (nested mixes choose independently).
float hash_hit(Vec3f p, Vec3f wo, int material) {
  uint64_t h = mix64(kMixSalt ^ uint64_t(uint32_t(material)));
  for (float v : {p.x, p.y, p.z, wo.x, wo.y, wo.z}) h = mix64(h ^ std::bit_cast<uint32_t>(v));
  return float(h >> 40) * 0x1p-24f;
}

// Depth-first over the mix graph: a component still on the stack closes a cycle.
void check_acyclic(const SceneDesc& scene, const std::vector<MaterialMix>& mixes) {
  enum : uint8_t { kUnseen, kOnStack, kDone };
  std::vector<uint8_t> state(mixes.size(), kUnseen);
  for (size_t root = 0; root < mixes.size(); ++root) {
    if (state[root] != kUnseen) continue;
    std::vector<std::pair<int, int>> stack{{int(root), 0}};  // material, next component to visit
    state[root] = kOnStack;
    while (!stack.empty()) {
      auto& [m, next] = stack.back();
      const MaterialMix& mix = mixes[size_t(m)];
      if (!mix.is_mix() || next == 2) {
        state[size_t(m)] = kDone;
        stack.pop_back();
        continue;
      }
      const int c = mix.materials[size_t(next++)];
      if (state[size_t(c)] == kOnStack)
        throw Error(scene.source_path, "Material id=" + std::to_string(scene.materials[size_t(c)].id),
                    "mix materials contain each other");
      if (state[size_t(c)] == kUnseen) {
        state[size_t(c)] = kOnStack;
        stack.emplace_back(c, 0);
      }
    }
  }
}

}  // namespace

std::vector<MaterialMix> build_material_mixes(const SceneDesc& scene) {
  const size_t n = scene.materials.size();
  std::vector<MaterialMix> mixes;
  for (size_t i = 0; i < n; ++i) {
    const auto& mix = scene.materials[i].mix;
    if (!mix) continue;
    if (mixes.empty()) mixes.resize(n);
    for (int c : mix->materials)
      if (c < 0 || size_t(c) >= n)
        throw Error(scene.source_path, "Material id=" + std::to_string(scene.materials[i].id),
                    "a mix names material index " + std::to_string(c) + ", not one of the " + std::to_string(n));
    mixes[i] = MaterialMix{mix->materials, mix->amount.value, mix->amount.texture};
  }
  if (mixes.empty()) return mixes;
  check_acyclic(scene, mixes);
  return mixes;
}

int mix_component(const std::vector<MaterialMix>& mixes, int material, float amount, Vec3f p, Vec3f wo) {
  const MaterialMix& m = mixes[size_t(material)];
  if (amount <= 0.0f) return m.materials[0];
  if (amount >= 1.0f) return m.materials[1];
  return amount < hash_hit(p, wo, material) ? m.materials[0] : m.materials[1];
}

int choose_mixed_material(const std::vector<MaterialMix>& mixes, int material, Vec3f p, Vec3f wo) {
  while (mixes[size_t(material)].is_mix() && !mixes[size_t(material)].textured())
    material = mix_component(mixes, material, mixes[size_t(material)].amount, p, wo);
  return material;
}

}  // namespace kiln
