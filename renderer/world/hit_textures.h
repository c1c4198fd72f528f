// The textures of a hit (renderer/texture/scene_textures.h) applied to its interaction: the texel's k_d / k_s, bump
// and normal maps, replace_all. Footprints of filtered textures are measured in the pixels of the camera being
// rendered, whose spread the render's context carries (renderer/integrators/render_context.h): the world's textures
// hold no per-render state.
#pragma once
#include "renderer/texture/footprint.h"
#include "renderer/texture/scene_textures.h"
#include "renderer/world/interaction.h"

namespace kiln {

// The footprint of a hit in its texture coordinates, from the camera's pixel spread (renderer/texture/footprint.h).
UvFootprint hit_footprint(const CameraSpread& camera, const SurfaceInteraction& si);

// Shading at a textured hit: sets si.material to `scratch` (the material with the texel's k_d / k_s) and bends
// si.ns by bump or normal maps. Returns true when a replace_all texture gives the surface's colour outright
// (`unlit`), without shading.
bool apply_textures(const SceneTextures& textures, const CameraSpread& camera, SurfaceInteraction& si,
                    Material& scratch, Rgb& unlit);

}  // namespace kiln
