// A pbrt-v4 scene rendered as `kiln render` renders it (its own rules, its PixelFilter or pbrt's default Gaussian)
// and compared with pbrt-v4's render by 16-px block luminance (renderer/analysis/image_compare.h): the side-by-side
// check of PbrtReference and PbrtFeatureScenes.
#pragma once
#include <iostream>
#include <string>

#include "renderer/analysis/image_compare.h"
#include "renderer/film/pixel_filter.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render_util.h"

namespace kiln::test {

inline constexpr int kReferenceBlock = 16;

// Renders camera 0 of `scene_path` at spp with `seed` and compares it with the EXR `reference_path`; prints the
// statistics under `name`.
inline BlockStats render_against_reference(const std::string& name, const std::string& scene_path,
                                           const std::string& reference_path, uint32_t spp, uint64_t seed) {
  const SceneDesc scene = load_scene(scene_path);
  const auto world = build_scene_world(scene);
  const CameraDesc& cd = scene.cameras.at(0);
  const Camera cam(cd);
  Film film(cam.width(), cam.height());
  RenderOptions ro;
  ro.seed = seed;
  ro.spp_total = spp;
  ro.filter = pixel_filter_for(cd, std::nullopt);
  render_samples(*world, cam, scene_settings(cd, scene, world->features), ro, 0, spp, film);
  const Image reference = read_exr(reference_path).rgb;
  const BlockStats st = block_luminance_stats(film.mean(), reference, kReferenceBlock);
  std::cout << name << " vs pbrt-v4, " << spp << " spp, " << kReferenceBlock << "-px blocks: median " << st.median_rel
            << ", p95 " << st.p95_rel << ", mean ratio " << st.mean_ratio << " over " << st.blocks << " blocks\n";
  return st;
}

}  // namespace kiln::test
