#include <cstdio>

#include "core/error.h"
#include "renderer/accel/check_bvh.h"
#include "renderer/world/camera.h"
#include "renderer/cli/commands.h"
#include "renderer/world/world.h"
#include "scenes/loader.h"

namespace kiln {

int cmd_check_bvh(const std::string& scene_path, size_t rays, uint64_t seed) {
  const SceneDesc scene = load_scene(scene_path);
  if (scene.cameras.empty()) throw Error(scene_path, "", "scene has no camera to shoot rays from");
  WorldOptions wo;
  wo.build_accelerator = false;  // check_bvh builds both accelerators itself
  const auto world = build_world(scene, wo);
  const Camera camera(scene.cameras[0]);
  const auto camera_ray = [&](size_t, Rng& rng) {
    const Vec2f p = rng.next_2d();
    Ray r = camera.generate_ray(p.x * float(camera.width()), p.y * float(camera.height()), rng.next_2d());
    if (world->geometry.has_motion) r.time = rng.next_float();  // every instant of the shutter, moving shapes too
    return r;
  };
  CheckBvhOptions o;
  o.rays = rays;
  o.seed = seed;
  const CheckBvhReport r = check_bvh(world->geometry, camera_ray, o);
  std::printf("%s\n", r.to_json().c_str());
  if (!r.passed) {
    std::fprintf(stderr, "kiln: check-bvh: %zu of %zu rays disagree beyond the %g budget (%s)\n",
                 r.total_bvh_suspect(), r.total_rays(), kCheckBvhMaxDisagreementRate, r.first_disagreement.c_str());
    return 1;
  }
  return 0;
}

}  // namespace kiln
