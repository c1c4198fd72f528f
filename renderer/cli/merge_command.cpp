#include <cstdio>

#include "renderer/cli/commands.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render/merge.h"

namespace kiln {

int cmd_merge(const std::vector<std::string>& parts, const std::string& output) {
  const MergeResult r = merge_parts(parts);
  Metadata meta = {{"kiln:version", KILN_VERSION},
                   {"kiln:merged_parts", std::to_string(parts.size())},
                   {"kiln:spp", std::to_string(r.max_samples)},
                   {"kiln:incomplete", r.complete() ? "false" : "true"}};
  meta.insert(meta.end(), r.frame.begin(), r.frame.end());
  if (!r.complete()) meta.emplace_back("kiln:missing", missing_metadata(r.missing));
  write_exr(output, r.image, r.aovs, meta);
  std::printf("%s\n", output.c_str());
  for (const SampleGap& g : r.missing)
    std::fprintf(stderr, "kiln: warning: %s: missing samples %llu:%llu of %llu in pixels %d,%d,%d,%d (render them with %s)\n",
                 output.c_str(), (unsigned long long)g.first, (unsigned long long)g.last, (unsigned long long)r.spp_total,
                 g.x0, g.x1, g.y0, g.y1, g.to_args().c_str());
  if (!r.complete()) std::fprintf(stderr, "kiln: warning: %s is incomplete (kiln:incomplete = true)\n", output.c_str());
  return 0;
}

}  // namespace kiln
