#include "scenes/subdivision.h"

#include "core/error.h"

namespace kiln {

MeshDesc loop_subdivide(const MeshDesc& mesh, int levels) {
  if (levels <= 0) return mesh;
  throw Error(mesh.name, "", "Loop subdivision is not implemented yet");
}

void apply_subdivision(SceneDesc& scene) {
  for (MeshDesc& m : scene.meshes)
    if (m.subdivide > 0) {
      m = loop_subdivide(m, m.subdivide);
      m.subdivide = 0;
    }
}

}  // namespace kiln
