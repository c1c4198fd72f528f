// A pbrt-v4 scene rendered as `kiln render` renders it (its own rules, its PixelFilter or pbrt's default Gaussian)
// and compared with pbrt-v4's render by 16-px block luminance (renderer/analysis/image_compare.h): the side-by-side
// check of PbrtReference and PbrtFeatureScenes.
#pragma once
#include <gtest/gtest.h>

#include <iostream>
#include <string>

#include "renderer/analysis/image_compare.h"
#include "renderer/film/pixel_filter.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render_util.h"
#include "support/shared_data.h"

namespace kiln::test {

inline constexpr int kReferenceBlock = 16;

// A rectangle of pixels, [x0, x1) x [y0, y1); empty (the default) for the whole image.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

inline Image cropped(const Image& img, const PixelRect& r) {
  if (r.empty()) return img;
  Image out(r.x1 - r.x0, r.y1 - r.y0);
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) out.at(x - r.x0, y - r.y0) = img.at(x, y);
  return out;
}

// Camera 0 of `scene_path` rendered at spp with `seed`.
inline Image render_like_kiln(const std::string& scene_path, uint32_t spp, uint64_t seed) {
  const SceneDesc scene = load_scene(scene_path);
  return render_like_kiln(scene, *build_scene_world(scene), spp, seed);
}

// Block statistics of `image` against `reference` over `crop` of both (the whole images when empty), printed under
// `name`.
inline BlockStats blocks_against_reference(const std::string& name, const Image& image, const Image& reference,
                                           const PixelRect& crop = {}) {
  const BlockStats st = block_luminance_stats(cropped(image, crop), cropped(reference, crop), kReferenceBlock);
  std::cout << name << " vs pbrt-v4, " << kReferenceBlock << "-px blocks: median " << st.median_rel << ", p95 "
            << st.p95_rel << ", mean ratio " << st.mean_ratio << " over " << st.blocks << " blocks\n";
  return st;
}

// A file of the pbrt feature scenes (../shared/scenes/pbrt/features/), e.g. "reference/materials.exr".
inline std::string feature_scene(const std::string& rel) { return shared_dir() + "/scenes/pbrt/features/" + rel; }

// The feature issues' limits for Kiln against pbrt-v4 over 16-px blocks: luminance median < 2%, p95 < 8%, mean ratio
// within 2%, and no pixel that is not finite.
inline void expect_within_feature_limits(const BlockStats& st, const std::string& what) {
  EXPECT_EQ(st.left_out.image, 0u) << what << ": pixels that are not finite";
  EXPECT_LT(st.median_rel, 0.02) << what;
  EXPECT_LT(st.p95_rel, 0.08) << what;
  EXPECT_NEAR(st.mean_ratio, 1.0, 0.02) << what;
}

// Renders camera 0 of `scene_path` at spp with `seed` and compares it with the EXR `reference_path`.
inline BlockStats render_against_reference(const std::string& name, const std::string& scene_path,
                                           const std::string& reference_path, uint32_t spp, uint64_t seed) {
  return blocks_against_reference(name + ", " + std::to_string(spp) + " spp", render_like_kiln(scene_path, spp, seed),
                                  read_exr(reference_path).rgb);
}

}  // namespace kiln::test
