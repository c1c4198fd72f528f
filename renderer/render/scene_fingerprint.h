// A scene's identity for split renders: a hash of the bytes of every file its loader read (the scene file and the
// PLY / OBJ / binary data it references), in read order. Paths are not hashed, so machines that mount the scene
// at different places agree; a changed mesh or a changed scene file gives another hash. Files the loaders do not
// read themselves (texture images, environment maps: SceneDesc::external_files) are not covered.
#pragma once
#include <cstdint>
#include <string>

#include "scenes/loader.h"

namespace kiln {

struct SceneFingerprint {
  std::string hash;  // 16 hex digits: XXH64 chained over the files' bytes
  size_t files = 0;
  uint64_t bytes = 0;
};

// load_scene that also fingerprints every file the load read.
SceneDesc load_scene_fingerprinted(const std::string& path, const LoadOptions& options, SceneFingerprint& fingerprint);

}  // namespace kiln
