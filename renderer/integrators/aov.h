// Arbitrary output variables for denoisers and compositing: first-hit albedo, shading normal (both with the hit's
// textures, bump and normal maps applied), depth, position, and the per-pixel variance of the beauty estimate.
// Written as extra EXR layers with the channel names other tools expect (Albedo.R/G/B, N.X/Y/Z, Z, P.X/Y/Z,
// Variance.R/G/B).
#pragma once
#include <string>
#include <vector>

#include "renderer/world/camera.h"
#include "renderer/film/film.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render/render.h"

namespace kiln {

enum AovFlag : uint32_t {
  kAovAlbedo = 1u << 0,
  kAovNormal = 1u << 1,
  kAovDepth = 1u << 2,
  kAovPosition = 1u << 3,
  kAovVariance = 1u << 4,
};

// "albedo,normal,depth,position,variance" (any subset, or "all"); throws kiln::Error on an unknown name.
uint32_t parse_aovs(const std::string& list);

// Geometric AOVs are averaged over `samples` stratified primary rays per pixel (a cheap pass: one ray each);
// variance comes from the film.
std::vector<AovLayer> render_aovs(const World& world, const Camera& camera, uint32_t flags, const Film& film,
                                  const RenderOptions& options, uint32_t samples);

}  // namespace kiln
