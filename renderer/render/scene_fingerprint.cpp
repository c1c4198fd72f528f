#include "renderer/render/scene_fingerprint.h"

// Header-only xxHash (Debian's libxxhash-dev): nothing to link, so the renderer stays free of OpenImageIO.
#define XXH_INLINE_ALL
#include <xxhash.h>

#include <cstdio>

#include "scenes/parse_util.h"

namespace kiln {

SceneDesc load_scene_fingerprinted(const std::string& path, const LoadOptions& options, SceneFingerprint& fingerprint) {
  uint64_t h = 0;
  size_t files = 0;
  uint64_t bytes = 0;
  // Each file's hash seeds the next, so the order and the boundaries between files count too.
  const FileReadObserver observer([&](const std::string&, std::string_view data) {
    h = XXH64(data.data(), data.size(), h);
    ++files;
    bytes += data.size();
  });
  SceneDesc scene = load_scene(path, options);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  fingerprint = SceneFingerprint{hex, files, bytes};
  return scene;
}

}  // namespace kiln
