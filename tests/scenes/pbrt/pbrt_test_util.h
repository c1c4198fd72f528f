// Inline pbrt scenes for the loader tests: an options block before the world a test writes (it ends with WorldBegin
// on line 4, so the world's first directive is on line 5), loaded as `dir`/scene.pbrt so that the files it names
// resolve against `dir`.
#pragma once
#include <string>

#include "core/error.h"
#include "scenes/pbrt/loader.h"

namespace kiln {

inline const std::string kPbrtTestHead =
    "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 8 "
    "\"integer yresolution\" 8\nWorldBegin\n";

inline SceneDesc parse_world(const std::string& world, const std::string& dir) {
  return parse_pbrt(kPbrtTestHead + world, dir + "/scene.pbrt");
}

// The kiln::Error message, or "" when the world loads.
inline std::string world_error(const std::string& world, const std::string& dir) {
  try {
    parse_world(world, dir);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace kiln
