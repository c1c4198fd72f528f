#include <cstdio>

#include "renderer/cli/commands.h"
#include "renderer/analysis/image_compare.h"
#include "renderer/image_io/image_io.h"

namespace kiln {

int cmd_compare(const std::string& image, const std::string& reference, int block) {
  const Image a = read_exr(image).rgb;
  const Image b = read_exr(reference).rgb;
  const BlockStats bs = block_luminance_stats(a, b, block);
  const ErrorStats es = error_stats(a, b);
  std::printf("{\"blocks\": %zu, \"block\": %d, \"block_median_rel\": %.6f, \"block_p95_rel\": %.6f, "
              "\"mean_luminance_ratio\": %.6f, \"mse\": %.6g, \"rmse\": %.6g, \"relmse\": %.6g, "
              "\"nonfinite_pixels\": %zu, \"nonfinite_reference_pixels\": %zu}\n",
              bs.blocks, block, bs.median_rel, bs.p95_rel, bs.mean_ratio, es.mse, es.rmse, es.rel_mse,
              es.left_out.image, es.left_out.reference);
  return 0;
}

}  // namespace kiln
