// Loop subdivision of triangle meshes (as pbrt's loopsubdiv: smooth interior and boundary rules).
#pragma once
#include "scenes/scene.h"

namespace kiln {

// Returns the mesh subdivided `levels` times (each level multiplies the triangle count by 4).
MeshDesc loop_subdivide(const MeshDesc& mesh, int levels);
// Applies each mesh's requested subdivision (MeshDesc::subdivide) in place.
void apply_subdivision(SceneDesc& scene);

}  // namespace kiln
