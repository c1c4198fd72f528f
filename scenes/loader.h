// Loads any scene Kiln understands, chosen by extension: .xml (CENG795), .json (CS171), .ply / .obj (a bare mesh
// with an automatic camera, ground plane and light).
#pragma once
#include <string>

#include "scenes/scene.h"

namespace kiln {

struct LoadOptions {
  int subdivide = -1;  // Loop subdivision levels applied to every mesh; < 0: the scene's own setting
};

// Throws kiln::Error naming the file, element or line, and what is wrong.
SceneDesc load_scene(const std::string& path, const LoadOptions& options = {});

}  // namespace kiln
