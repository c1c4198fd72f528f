// The textures of a hit (renderer/texture/scene_textures.h) applied to its interaction: the texel's k_d / k_s, bump
// and normal maps, replace_all, and pbrt-v4 materials resolved per hit (renderer/texture/textured_material.h). Footprints of filtered textures are measured in the pixels of the camera being
// rendered, whose spread the render's context carries (renderer/integrators/render_context.h): the world's textures
// hold no per-render state.
#pragma once
#include "renderer/texture/footprint.h"
#include "renderer/texture/scene_textures.h"
#include "renderer/world/interaction.h"
#include "renderer/world/world.h"

namespace kiln {

// The footprint of a hit in its texture coordinates, from the camera's pixel spread (renderer/texture/footprint.h).
UvFootprint hit_footprint(const CameraSpread& camera, const SurfaceInteraction& si);

// Shading at a textured hit (si.textures >= 0) of world w: sets si.material to `scratch` (the material with the
// texel's k_d / k_s, or a pbrt-v4 material built from its textures' values there), or to the component a mix with a
// textured amount chooses there (renderer/world/material_mix.h), and bends si.ns by bump or normal maps. pbrt-v4 textures' footprints are `camera`'s narrowed by pbrt_footprint_scale (footprint_scale_for_spp).
// Returns true when a replace_all texture gives the surface's colour outright (`unlit`), without shading.
bool apply_textures(const World& w, const CameraSpread& camera, float pbrt_footprint_scale, SurfaceInteraction& si,
                    Material& scratch, Rgb& unlit);

}  // namespace kiln
