// Loads any scene Kiln understands, chosen by extension: .xml (CENG795), .json (CS171), .pbrt (pbrt-v4), .ply / .obj
// (a bare mesh with an automatic camera, ground plane and light).
#pragma once
#include <string>

#include "scenes/scene.h"

namespace kiln {

struct LoadOptions {
  // Loop subdivision levels for the meshes the scene marks (all meshes when it marks none); < 0: the scene's own.
  int subdivide = -1;
  // Leave MeshDesc::subdivide set but do not subdivide yet (kiln profile times subdivision on its own).
  bool defer_subdivision = false;
  // pbrt: missing PLY meshes and included files are reported and left out instead of failing the load
  // (scenes/pbrt/loader.h PbrtOptions).
  bool allow_missing_files = false;
};

// Throws kiln::Error naming the file, element or line, and what is wrong.
SceneDesc load_scene(const std::string& path, const LoadOptions& options = {});

}  // namespace kiln
