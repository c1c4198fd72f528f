// What a camera sample sees (pbrt-v4's VisibleSurface): the first surface of its path that is not a pure mirror or
// glass, recorded by the integrator for the geometric AOVs and added to the film beside the sample's colour, with
// the same filter weight (renderer/film/film.h). Mirrors and glass are looked through, as denoisers expect: their
// albedo and normal say little about the image, the surface seen in them does.
#pragma once
#include "core/color.h"
#include "core/vec.h"

namespace kiln {

struct VisibleSurface {
  Rgb albedo{0.0f};  // the material's reflectance colour at the hit, textures applied, clamped to [0, 1]
  Vec3f n{0.0f};     // unit shading normal after bump and normal maps, turned towards the arriving ray
  Vec3f p{0.0f};     // world-space position
  float z = 0.0f;    // distance travelled from the camera along the path (through mirrors: the mirror image's depth)
  bool found = false;  // false: the path left the scene or ended before such a surface (adds zero, like a miss)
};

}  // namespace kiln
