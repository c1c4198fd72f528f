// Combines partial renders (crops and/or sample ranges of one frame, from `kiln render --crop --spp-range`) into
// the frame a single run produces: each part's pixels are weighted by its sample count and placed by its data
// window, its AOV layers too (renderer/integrators/aov.h: filtered means like the colour; the variance of the mean
// combines as that of the merged mean). Every part must carry the same AOV channels.
//
// Before any pixel is read, the parts' metadata must show they belong to one frame and fit together:
//  - same scene (kiln:scene_hash, the bytes of every file the scene was loaded from), camera, seed, resolution,
//    total spp (kiln:spp_total), integrator and render options;
//  - no part is an interrupted render (kiln:incomplete = true: its pixels hold unequal sample counts);
//  - no two parts share a sample of a pixel (a duplicate, e.g. one file given twice, or an overlap).
// Any violation throws kiln::Error naming the files (exit 2). Samples no part covers are reported, not refused.
#pragma once
#include <string>
#include <vector>

#include "core/image.h"
#include "renderer/image_io/image_io.h"

namespace kiln {

// Pixels [x0, x1) x [y0, y1) lack the samples [first, last): the `--crop` and `--spp-range` that render them.
struct SampleGap {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  uint64_t first = 0, last = 0;
  std::string to_args() const;  // "--crop x0,x1,y0,y1 --spp-range first:last"
};

struct MergeResult {
  Image image;
  std::vector<AovLayer> aovs;     // the parts' AOV layers merged like the colour (one layer per channel)
  uint64_t spp_total = 0;         // the frame's samples per pixel
  uint64_t max_samples = 0;       // the most samples any pixel received (spp_total when complete)
  Metadata frame;                 // the identity keys every part shares (scene, camera, seed, ...)
  std::vector<SampleGap> missing;  // empty when every sample of every pixel came from exactly one part
  bool complete() const { return missing.empty(); }
};

MergeResult merge_parts(const std::vector<std::string>& parts);

// The gaps as the merged image's kiln:missing value: "x0,x1,y0,y1 first:last" per gap, ';'-separated.
std::string missing_metadata(const std::vector<SampleGap>& gaps);

}  // namespace kiln
