// Participating media of a world (media/) built from the scene's descriptions; NanoVDB files are read here.
#pragma once
#include "media/medium.h"
#include "renderer/world/world.h"
#include "scenes/scene.h"

namespace kiln {

// Throws kiln::Error naming where the medium is defined (MediumDesc::element) when its data cannot be used.
Medium build_medium(const MediumDesc& desc);

// Whether the scene uses its media: a shape with different media on its two sides, or a camera inside one.
bool scene_uses_media(const SceneDesc& scene);

// Builds every medium of the scene into w.media and records them in w.stats.
void build_world_media(const SceneDesc& scene, World& w);

}  // namespace kiln
