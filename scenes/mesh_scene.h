// A quick-look scene around a bare mesh (kiln render MESH.ply): automatic camera, ground plane and light.
#pragma once
#include <string>

#include "scenes/scene.h"

namespace kiln {

SceneDesc make_mesh_scene(MeshDesc mesh, const std::string& path);

}  // namespace kiln
