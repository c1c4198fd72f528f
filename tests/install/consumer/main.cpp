// Loads a scene and builds its world through the installed Kiln libraries.
#include <cstdio>

#include "renderer/world/world.h"
#include "scenes/loader.h"

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const kiln::SceneDesc scene = kiln::load_scene(argv[1]);
  const auto world = kiln::build_world(scene, {});
  std::printf("%zu triangles\n", world->stats.triangles);
  return world->stats.triangles > 0 ? 0 : 1;
}
