#include "scenes/loader.h"

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scenes/json_loader.h"
#include "scenes/mesh_scene.h"
#include "scenes/obj_loader.h"
#include "scenes/pbrt/loader.h"
#include "scenes/ply_loader.h"
#include "scenes/subdivision.h"
#include "scenes/xml_loader.h"

namespace kiln {

SceneDesc load_scene(const std::string& path, const LoadOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path, "", "file not found");
  if (fs::is_directory(path, ec)) throw Error(path, "", "is a directory, not a scene file");
  if (!std::ifstream(path).good()) throw Error(path, "", "cannot be opened for reading");
  std::string ext = fs::path(path).extension().string();
  for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".gz") ext = fs::path(path).stem().extension().string() + ext;  // scene.pbrt.gz
  SceneDesc scene;
  if (ext == ".xml") {
    scene = load_ceng795_xml(path);
  } else if (ext == ".json") {
    scene = load_cs171_json(path);
  } else if (ext == ".ply") {
    scene = make_mesh_scene(load_ply(path), path);
  } else if (ext == ".obj") {
    scene = make_mesh_scene(load_obj(path), path);
  } else if (ext == ".pbrt" || ext == ".pbrt.gz") {
    scene = load_pbrt(path, PbrtOptions{options.allow_missing_files});
  } else {
    throw Error(path, "", "unknown scene format '" + ext + "' (expected .xml, .json, .pbrt, .ply or .obj)");
  }
  if (options.subdivide > kMaxSubdivisionLevels)
    throw Error("--subdivide", "", "at most " + std::to_string(kMaxSubdivisionLevels) + " levels");
  if (options.subdivide >= 0) {
    // --subdivide overrides the level of the meshes the scene marks for subdivision; a scene that marks none
    // (or a bare PLY/OBJ) has all its meshes subdivided.
    bool any_marked = false;
    for (const MeshDesc& m : scene.meshes) any_marked |= m.subdivide > 0;
    for (MeshDesc& m : scene.meshes)
      if (!any_marked || m.subdivide > 0) m.subdivide = options.subdivide;
  }
  if (!options.defer_subdivision) apply_subdivision(scene);
  return scene;
}

}  // namespace kiln
