// Arbitrary output variables for denoisers and compositing: albedo (textured), shading normal (after bump and normal
// maps), depth and position of what each camera sample sees (renderer/film/visible_surface.h: recorded by the
// integrators in the sample loop and filtered by the film like the colour), and the per-pixel variance of the
// beauty estimate. Written as extra EXR layers with the channel names other tools expect (Albedo.R/G/B, N.X/Y/Z, Z,
// P.X/Y/Z, Variance.R/G/B).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "materials/material.h"
#include "renderer/film/film.h"
#include "renderer/image_io/image_io.h"

namespace kiln {

enum AovFlag : uint32_t {
  kAovAlbedo = 1u << 0,
  kAovNormal = 1u << 1,
  kAovDepth = 1u << 2,
  kAovPosition = 1u << 3,
  kAovVariance = 1u << 4,
};
// The AOVs a film must keep surfaces for (Film::keep_surfaces).
inline constexpr uint32_t kAovSurface = kAovAlbedo | kAovNormal | kAovDepth | kAovPosition;

// "albedo,normal,depth,position,variance" (any subset, or "all"); throws kiln::Error on an unknown name.
uint32_t parse_aovs(const std::string& list);

// Albedo as denoisers expect it: the material's reflectance colour, each channel at most 1.
Rgb material_albedo(const Material& m);

// The full frame's layers that `flags` ask for, from the film (which keeps surfaces when a geometric AOV is asked).
std::vector<AovLayer> aov_layers(const Film& film, uint32_t flags);

}  // namespace kiln
