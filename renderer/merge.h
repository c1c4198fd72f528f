// Combines partial renders (crops and/or sample ranges of one frame, from `kiln render --crop --spp-range`) into
// the frame a single run produces: each part's pixels are weighted by its sample count and placed by its data
// window.
#pragma once
#include <string>
#include <vector>

#include "core/image.h"

namespace kiln {

struct MergeResult {
  Image image;
  uint64_t max_samples = 0;  // largest per-pixel sample count
  bool complete = true;      // every pixel received the same number of samples
};

// Throws kiln::Error for unreadable parts, parts of different frame sizes or parts without Kiln's sample metadata.
MergeResult merge_parts(const std::vector<std::string>& parts);

}  // namespace kiln
