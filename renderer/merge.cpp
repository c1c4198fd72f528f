#include "renderer/merge.h"

#include "core/error.h"
#include "renderer/image_io.h"

namespace kiln {

MergeResult merge_parts(const std::vector<std::string>& parts) {
  if (parts.empty()) throw Error("kiln merge: no input parts");
  std::vector<double> sum;
  std::vector<uint64_t> count;
  int fw = -1, fh = -1;
  for (const std::string& path : parts) {
    const ExrFile f = read_exr(path);
    const std::string first = f.find("kiln:spp_first"), last = f.find("kiln:spp_last");
    if (first.empty() || last.empty()) throw Error(path, "", "has no kiln:spp_first / kiln:spp_last metadata (not a Kiln part)");
    const uint64_t n = std::stoull(last) - std::stoull(first);
    if (fw < 0) {
      fw = f.window.full_width;
      fh = f.window.full_height;
      sum.assign(size_t(fw) * size_t(fh) * 3, 0.0);
      count.assign(size_t(fw) * size_t(fh), 0);
    } else if (fw != f.window.full_width || fh != f.window.full_height) {
      throw Error(path, "", "frame size differs from the first part");
    }
    for (int y = 0; y < f.rgb.height(); ++y)
      for (int x = 0; x < f.rgb.width(); ++x) {
        const int X = x + f.window.x, Y = y + f.window.y;
        if (X < 0 || Y < 0 || X >= fw || Y >= fh) throw Error(path, "", "data window lies outside the frame");
        const size_t i = size_t(Y) * size_t(fw) + size_t(X);
        const Rgb& c = f.rgb.at(x, y);
        sum[3 * i] += double(c.r) * double(n);
        sum[3 * i + 1] += double(c.g) * double(n);
        sum[3 * i + 2] += double(c.b) * double(n);
        count[i] += n;
      }
  }
  MergeResult r;
  r.image = Image(fw, fh);
  for (size_t i = 0; i < count.size(); ++i) {
    r.max_samples = std::max(r.max_samples, count[i]);
    if (count[i] == 0) continue;
    const double inv = 1.0 / double(count[i]);
    r.image.pixels()[i] = Rgb(float(sum[3 * i] * inv), float(sum[3 * i + 1] * inv), float(sum[3 * i + 2] * inv));
  }
  for (uint64_t c : count) r.complete &= (c == r.max_samples);
  return r;
}

}  // namespace kiln
