#include "renderer/render/merge.h"

#include <algorithm>
#include <charconv>
#include <tuple>

#include "core/error.h"
#include "renderer/render/scene_fingerprint.h"

namespace kiln {
namespace {

// Keys written by `kiln render` (renderer/cli/render_command.cpp) that identify the frame a part belongs to, and
// what they mean in an error message.
struct IdentityKey {
  const char* key;
  const char* what;
};
constexpr const char* kSceneHashKey = "kiln:scene_hash";
constexpr const char* kSceneFilesKey = "kiln:scene_files";
constexpr IdentityKey kIdentityKeys[] = {
    {kSceneHashKey, "scene (hash of its files)"},
    {"kiln:camera", "camera"},
    {"kiln:seed", "seed"},
    {"kiln:spp_total", "total spp"},
    {"kiln:integrator", "integrator"},
    {"kiln:render_options", "render options"},
};

struct Part {
  std::string path;
  ExrHeader header;
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // data window in the frame
  uint64_t first = 0, last = 0;         // sample range
};

std::string pixels_text(int x0, int x1, int y0, int y1) {
  return std::to_string(x0) + "," + std::to_string(x1) + "," + std::to_string(y0) + "," + std::to_string(y1);
}

std::string samples_text(uint64_t first, uint64_t last) { return std::to_string(first) + ":" + std::to_string(last); }

uint64_t parse_count(const std::string& path, const std::string& key, const std::string& text) {
  uint64_t v = 0;
  const char* end = text.data() + text.size();
  const auto [p, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || p != end)
    throw Error(path, key, "expected a sample count, got '" + text + "'");
  return v;
}

Part read_part(const std::string& path) {
  Part p;
  p.path = path;
  p.header = read_exr_header(path);
  const ExrHeader& h = p.header;
  const std::string first = h.find("kiln:spp_first"), last = h.find("kiln:spp_last");
  if (first.empty() || last.empty())
    throw Error(path, "", "has no kiln:spp_first / kiln:spp_last metadata (not a Kiln part)");
  for (const IdentityKey& k : kIdentityKeys)
    if (h.find(k.key).empty())
      throw Error(path, "", std::string("has no ") + k.key + " metadata (written by an older kiln?): render it again");
  p.first = parse_count(path, "kiln:spp_first", first);
  p.last = parse_count(path, "kiln:spp_last", last);
  const uint64_t total = parse_count(path, "kiln:spp_total", h.find("kiln:spp_total"));
  if (p.first >= p.last || p.last > total)
    throw Error(path, "", "sample range " + samples_text(p.first, p.last) + " is empty or beyond the frame's " +
                              std::to_string(total) + " spp");
  p.x0 = h.window.x;
  p.y0 = h.window.y;
  p.x1 = h.window.x + h.width;
  p.y1 = h.window.y + h.height;
  if (h.find("kiln:incomplete") == "true")
    throw Error(path, "", "is an interrupted render (kiln:incomplete): its pixels hold unequal sample counts; render it again (" +
                              SampleGap{p.x0, p.x1, p.y0, p.y1, p.first, p.last}.to_args() + ")");
  if (p.x0 < 0 || p.y0 < 0 || p.x1 > h.window.full_width || p.y1 > h.window.full_height || p.x0 >= p.x1 || p.y0 >= p.y1)
    throw Error(path, "", "data window " + pixels_text(p.x0, p.x1, p.y0, p.y1) + " lies outside the " +
                              std::to_string(h.window.full_width) + "x" + std::to_string(h.window.full_height) + " frame");
  return p;
}

// The first scene file whose hash differs between two parts (renderer/render/scene_fingerprint.h), as a clause of
// the refusal; empty when the parts' scenes agree or a part lists no files (written by an older kiln).
std::string file_difference(const Part& p, const Part& ref) {
  if (p.header.find(kSceneHashKey) == ref.header.find(kSceneHashKey)) return "";
  const auto a = parse_scene_files_metadata(p.header.find(kSceneFilesKey));
  const auto b = parse_scene_files_metadata(ref.header.find(kSceneFilesKey));
  if (a.empty() || b.empty()) return "";
  const auto d = first_file_difference(a, b);
  return d ? "; first scene file that differs: " + *d : "";
}

void check_same_frame(const Part& p, const Part& ref) {
  const DataWindow &a = p.header.window, &b = ref.header.window;
  if (a.full_width != b.full_width || a.full_height != b.full_height)
    throw Error(p.path, "", "resolution " + std::to_string(a.full_width) + "x" + std::to_string(a.full_height) +
                                " differs from " + ref.path + " (" + std::to_string(b.full_width) + "x" +
                                std::to_string(b.full_height) + "); a merge combines parts of one frame only");
  for (const IdentityKey& k : kIdentityKeys) {
    const std::string va = p.header.find(k.key), vb = ref.header.find(k.key);
    if (va != vb)
      throw Error(p.path, "", std::string(k.what) + " differs from " + ref.path + " (" + k.key + " '" + va + "' vs '" +
                                  vb + "'" + file_difference(p, ref) + "); a merge combines parts of one frame only");
  }
}

void check_disjoint(const Part& b, const Part& a) {
  const int x0 = std::max(a.x0, b.x0), x1 = std::min(a.x1, b.x1), y0 = std::max(a.y0, b.y0), y1 = std::min(a.y1, b.y1);
  const uint64_t f = std::max(a.first, b.first), l = std::min(a.last, b.last);
  if (x0 >= x1 || y0 >= y1 || f >= l) return;
  const bool same = a.x0 == b.x0 && a.x1 == b.x1 && a.y0 == b.y0 && a.y1 == b.y1 && a.first == b.first && a.last == b.last;
  if (same)
    throw Error(b.path, "", "duplicates " + a.path + " (both cover pixels " + pixels_text(x0, x1, y0, y1) + ", samples " +
                                samples_text(f, l) + "); every sample must come from one part");
  throw Error(b.path, "", "overlaps " + a.path + " in pixels " + pixels_text(x0, x1, y0, y1) + ", samples " +
                              samples_text(f, l) + "; every sample must come from one part");
}

// The samples [0, total) minus the (disjoint) ranges given.
std::vector<std::pair<uint64_t, uint64_t>> gaps(std::vector<std::pair<uint64_t, uint64_t>> covered, uint64_t total) {
  std::sort(covered.begin(), covered.end());
  std::vector<std::pair<uint64_t, uint64_t>> out;
  uint64_t at = 0;
  for (const auto& [f, l] : covered) {
    if (f > at) out.emplace_back(at, f);
    at = std::max(at, l);
  }
  if (at < total) out.emplace_back(at, total);
  return out;
}

// Cuts the frame along every part's window edges; within a cell the covering parts are the same, so its missing
// samples are one list. Neighbouring cells with the same list are joined (along x, then along y) to keep the report
// short: an spp split gives one rectangle per missing range, a band split one per missing band.
std::vector<SampleGap> find_missing(const std::vector<Part>& parts, int width, int height, uint64_t total) {
  std::vector<int> xs = {0, width}, ys = {0, height};
  for (const Part& p : parts) {
    xs.insert(xs.end(), {p.x0, p.x1});
    ys.insert(ys.end(), {p.y0, p.y1});
  }
  for (auto* v : {&xs, &ys}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  using Ranges = std::vector<std::pair<uint64_t, uint64_t>>;
  struct Run {
    int x0, x1, y0, y1;
    Ranges missing;
  };
  std::vector<Run> runs, open;  // open: runs of the previous band that may still grow downwards
  for (size_t j = 0; j + 1 < ys.size(); ++j) {
    std::vector<Run> band;
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
      Ranges covered;
      for (const Part& p : parts)
        if (p.x0 <= xs[i] && xs[i + 1] <= p.x1 && p.y0 <= ys[j] && ys[j + 1] <= p.y1) covered.emplace_back(p.first, p.last);
      Ranges miss = gaps(std::move(covered), total);
      if (!band.empty() && band.back().x1 == xs[i] && band.back().missing == miss)
        band.back().x1 = xs[i + 1];
      else
        band.push_back(Run{xs[i], xs[i + 1], ys[j], ys[j + 1], std::move(miss)});
    }
    std::vector<Run> next;
    for (Run& r : band) {
      auto above = std::find_if(open.begin(), open.end(), [&](const Run& o) {
        return o.x0 == r.x0 && o.x1 == r.x1 && o.y1 == r.y0 && o.missing == r.missing;
      });
      if (above != open.end()) {
        r.y0 = above->y0;
        open.erase(above);
      }
      next.push_back(std::move(r));
    }
    runs.insert(runs.end(), open.begin(), open.end());
    open = std::move(next);
  }
  runs.insert(runs.end(), open.begin(), open.end());
  std::vector<SampleGap> out;
  for (const Run& r : runs)
    for (const auto& [f, l] : r.missing) out.push_back(SampleGap{r.x0, r.x1, r.y0, r.y1, f, l});
  std::sort(out.begin(), out.end(), [](const SampleGap& a, const SampleGap& b) {
    return std::tie(a.first, a.y0, a.x0) < std::tie(b.first, b.y0, b.x0);
  });
  return out;
}

// The AOV channels of a part (one layer per channel, as read_exr returns them), in file order.
std::vector<std::string> aov_channels(const ExrFile& f) {
  std::vector<std::string> names;
  for (const AovLayer& l : f.aovs) names.insert(names.end(), l.channels.begin(), l.channels.end());
  return names;
}

void check_same_channels(const std::string& path, const std::vector<std::string>& have, const std::string& ref_path,
                         const std::vector<std::string>& want) {
  if (have == want) return;
  const auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& c : v) s += (s.empty() ? "" : ",") + c;
    return s.empty() ? std::string("none") : s;
  };
  throw Error(path, "", "AOV channels (" + join(have) + ") differ from " + ref_path + " (" + join(want) +
                            "); render every part with the same --aov");
}

// A per-pixel variance of the mean (the Variance AOV) combines as the variance of the merged mean, sum n_i^2 v_i /
// N^2 over independent parts; every other channel is a per-pixel mean like the colour, sum n_i v_i / N.
bool is_variance(const std::string& channel) { return channel.rfind("Variance.", 0) == 0; }

// Every part's pixels weighted by its sample count, placed by its data window.
struct FrameSums {
  int width, height;
  std::vector<double> rgb;                   // 3 per pixel
  std::vector<std::vector<double>> channel;  // per AOV channel, 1 per pixel
  std::vector<uint64_t> count;               // samples per pixel

  FrameSums(int w, int h) : width(w), height(h), rgb(size_t(w) * size_t(h) * 3, 0.0), count(size_t(w) * size_t(h), 0) {}

  void add(const Part& p, const ExrFile& f, const std::vector<std::string>& channels) {
    channel.resize(channels.size(), std::vector<double>(count.size(), 0.0));
    const double n = double(p.last - p.first);
    for (int y = 0; y < f.rgb.height(); ++y)
      for (int x = 0; x < f.rgb.width(); ++x) {
        const size_t i = size_t(y + p.y0) * size_t(width) + size_t(x + p.x0);
        const size_t local = size_t(y) * size_t(f.rgb.width()) + size_t(x);
        const Rgb& c = f.rgb.at(x, y);
        rgb[3 * i] += double(c.r) * n;
        rgb[3 * i + 1] += double(c.g) * n;
        rgb[3 * i + 2] += double(c.b) * n;
        count[i] += p.last - p.first;
        for (size_t k = 0; k < channels.size(); ++k)
          channel[k][i] += double(f.aovs[k].data[local]) * (is_variance(channels[k]) ? n * n : n);
      }
  }

  Image image() const {
    Image img(width, height);
    for (size_t i = 0; i < count.size(); ++i) {
      if (count[i] == 0) continue;
      const double inv = 1.0 / double(count[i]);
      img.pixels()[i] = Rgb(float(rgb[3 * i] * inv), float(rgb[3 * i + 1] * inv), float(rgb[3 * i + 2] * inv));
    }
    return img;
  }

  std::vector<AovLayer> layers(const std::vector<std::string>& channels) const {
    std::vector<AovLayer> out;
    for (size_t k = 0; k < channels.size(); ++k) {
      AovLayer l{{channels[k]}, std::vector<float>(count.size(), 0.0f)};
      for (size_t i = 0; i < count.size(); ++i) {
        if (count[i] == 0) continue;
        const double inv = 1.0 / double(count[i]);
        l.data[i] = float(channel[k][i] * (is_variance(channels[k]) ? inv * inv : inv));
      }
      out.push_back(std::move(l));
    }
    return out;
  }
};

}  // namespace

std::string SampleGap::to_args() const {
  return "--crop " + pixels_text(x0, x1, y0, y1) + " --spp-range " + samples_text(first, last);
}

std::string missing_metadata(const std::vector<SampleGap>& gaps) {
  std::string s;
  for (const SampleGap& g : gaps) {
    if (!s.empty()) s.push_back(';');
    s.append(pixels_text(g.x0, g.x1, g.y0, g.y1)).append(" ").append(samples_text(g.first, g.last));
  }
  return s;
}

MergeResult merge_parts(const std::vector<std::string>& paths) {
  if (paths.empty()) throw Error("kiln merge: no input parts");
  std::vector<Part> parts;
  for (const std::string& path : paths) parts.push_back(read_part(path));
  for (size_t i = 1; i < parts.size(); ++i) check_same_frame(parts[i], parts[0]);
  for (size_t j = 1; j < parts.size(); ++j)
    for (size_t i = 0; i < j; ++i) check_disjoint(parts[j], parts[i]);

  const int fw = parts[0].header.window.full_width, fh = parts[0].header.window.full_height;
  FrameSums sums(fw, fh);
  std::vector<std::string> channels;  // the AOV channels of the first part, which every part must have
  for (const Part& p : parts) {
    const ExrFile f = read_exr(p.path);
    if (f.rgb.width() != p.x1 - p.x0 || f.rgb.height() != p.y1 - p.y0) throw Error(p.path, "", "pixels differ from its header");
    if (&p == &parts[0]) channels = aov_channels(f);
    else check_same_channels(p.path, aov_channels(f), parts[0].path, channels);
    sums.add(p, f, channels);
  }
  MergeResult r;
  r.image = sums.image();
  r.aovs = sums.layers(channels);
  r.max_samples = *std::max_element(sums.count.begin(), sums.count.end());
  r.spp_total = parse_count(parts[0].path, "kiln:spp_total", parts[0].header.find("kiln:spp_total"));
  for (const IdentityKey& k : kIdentityKeys) r.frame.emplace_back(k.key, parts[0].header.find(k.key));
  r.frame.emplace_back("kiln:scene", parts[0].header.find("kiln:scene"));
  r.frame.emplace_back(kSceneFilesKey, parts[0].header.find(kSceneFilesKey));
  r.missing = find_missing(parts, fw, fh, r.spp_total);
  return r;
}

}  // namespace kiln
