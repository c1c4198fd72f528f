// Shapes' "alpha" (pbrt-v4: a float or a float texture on any shape): cut-outs, read into ShapeAlphaDesc
// (scenes/scene.h). The texture is any float texture of the scene's texture graph (scenes/pbrt/textures.cpp), read
// at the hit as material parameters read theirs.
#include "scenes/pbrt/builder.h"

namespace kiln {

ShapeAlphaDesc PbrtBuilder::shape_alpha(const PbrtParams& ps) {
  const TexturedFloat a = float_param(ps, "alpha", 1.0f);
  return ShapeAlphaDesc{a.value, a.texture};
}

}  // namespace kiln
