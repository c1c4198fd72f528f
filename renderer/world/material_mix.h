// Mix materials (pbrt-v4 "mix", SceneDesc's MaterialMixDesc): a material that is, at each hit, one of two others,
// the second with probability `amount`. As in pbrt-v4 the choice is a deterministic hash of the hit (its position
// and the direction towards the viewer), so the image is the blend of the two in expectation, every hit shades
// with a plain material, and the same hit always makes the same choice (images stay bit-identical for any thread
// count). Components may be mixes themselves: the choice repeats, with an independent hash, until a plain
// material is reached (the world rejects cycles when it is built).
//
// A constant amount is chosen on when the interaction is made (make_interaction), before any texture is looked up.
// A textured amount stops that choice at its mix: the shape is bound to the scene's textures and the choice goes
// on where the hit's textures are evaluated (renderer/world/hit_textures.h), with the amount texture's value there.
#pragma once
#include <array>
#include <vector>

#include "core/vec.h"
#include "scenes/scene.h"

namespace kiln {

struct MaterialMix {
  std::array<int, 2> materials{-1, -1};  // indices into World::materials; -1: not a mix
  float amount = 0.5f;                   // probability of materials[1]; <= 0 always materials[0], >= 1 materials[1]
  int amount_texture = -1;               // a float texture (SceneDesc::pbrt_textures) that gives `amount` per hit
  bool is_mix() const { return materials[0] >= 0; }
  bool textured() const { return amount_texture >= 0; }
};

// One entry per material of the scene (empty when it has no mix), checked: components in range and no mix that
// (indirectly) contains itself (kiln::Error naming the material).
std::vector<MaterialMix> build_material_mixes(const SceneDesc& scene);

// The component that mix `material` (mixes[material]) chooses at a hit at p seen from wo when its amount there is
// `amount`.
int mix_component(const std::vector<MaterialMix>& mixes, int material, float amount, Vec3f p, Vec3f wo);

// The material a hit at p seen from wo shades with: a plain one, or the first mix on the way whose amount is
// textured (its choice needs the hit's textures). mixes: one entry per material (World::mixes).
int choose_mixed_material(const std::vector<MaterialMix>& mixes, int material, Vec3f p, Vec3f wo);

}  // namespace kiln
