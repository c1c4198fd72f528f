// `kiln merge` accepts only parts of one frame that fit together (issue 20): each refusal names the files, and
// samples no part covers are reported as --crop / --spp-range gaps. Parts here are written directly with the
// metadata `kiln render` writes, so every case is exact and fast; the scene fingerprint is tested on real files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>

#include "core/error.h"
#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"
#include "renderer/render/merge.h"
#include "renderer/render/scene_fingerprint.h"

namespace kiln::test {
namespace {

namespace fs = std::filesystem;

// One part of a 16x8 frame of 8 spp: a crop (x0,x1,y0,y1) and a sample range, every pixel holding `value`.
struct PartSpec {
  int x0 = 0, x1 = 16, y0 = 0, y1 = 8;
  uint64_t first = 0, last = 8;
  float value = 1.0f;
  int full_width = 16, full_height = 8;
  Metadata overrides;  // replace (or, with an empty value, drop) the default metadata
};

Metadata part_metadata(const PartSpec& p) {
  Metadata m = {{"kiln:version", KILN_VERSION},
                {"kiln:scene", "scene.xml"},
                {"kiln:camera", "1"},
                {"kiln:spp", std::to_string(p.last - p.first)},
                {"kiln:spp_first", std::to_string(p.first)},
                {"kiln:spp_last", std::to_string(p.last)},
                {"kiln:spp_total", "8"},
                {"kiln:scene_hash", "0123456789abcdef"},
                {"kiln:scene_files", "2"},
                {"kiln:seed", "0"},
                {"kiln:integrator", "path tracing: brdf+nee+mis, max depth 8"},
                {"kiln:render_options", "clamp=0.000000 physical_lights=0 subdivide=-1"},
                {"kiln:incomplete", "false"}};
  for (const auto& [k, v] : p.overrides) {
    auto it = std::find_if(m.begin(), m.end(), [&](const auto& e) { return e.first == k; });
    if (it != m.end()) m.erase(it);
    if (!v.empty()) m.emplace_back(k, v);
  }
  return m;
}

std::string write_part(const std::string& name, const PartSpec& p) {
  const std::string path = tmp_dir("merge_checks") + "/" + name;
  Image img(p.x1 - p.x0, p.y1 - p.y0);
  for (Rgb& c : img.pixels()) c = Rgb(p.value);
  write_exr(path, img, {}, part_metadata(p), DataWindow{p.x0, p.y0, p.full_width, p.full_height});
  return path;
}

// The kiln::Error message of merging `parts`; fails the test when the merge succeeds.
std::string merge_error(const std::vector<std::string>& parts) {
  try {
    merge_parts(parts);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "merge accepted the parts";
  return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(MergeChecks, WeightsPartsBySampleCount) {
  const std::string a = write_part("w_a.exr", {.first = 0, .last = 2, .value = 1.0f});
  const std::string b = write_part("w_b.exr", {.first = 2, .last = 8, .value = 3.0f});
  const MergeResult r = merge_parts({a, b});
  EXPECT_TRUE(r.complete());
  EXPECT_EQ(r.spp_total, 8u);
  for (const Rgb& c : r.image.pixels()) EXPECT_FLOAT_EQ(c.r, (2 * 1.0f + 6 * 3.0f) / 8);
}

// Each identity key: a part that differs in it is refused, naming both files and the key.
TEST(MergeChecks, RefusesPartsOfAnotherFrame) {
  const std::string a = write_part("id_a.exr", {.first = 0, .last = 4});
  const std::pair<const char*, const char*> keys[] = {
      {"kiln:scene_hash", "fedcba9876543210"}, {"kiln:camera", "2"},
      {"kiln:seed", "1"},                      {"kiln:spp_total", "16"},
      {"kiln:integrator", "path tracing: brdf+nee, max depth 8"},
      {"kiln:render_options", "clamp=10.000000 physical_lights=0 subdivide=-1"}};
  for (const auto& [key, value] : keys) {
    const std::string b = write_part("id_b.exr", {.first = 4, .last = 8, .overrides = {{key, value}}});
    const std::string msg = merge_error({a, b});
    EXPECT_TRUE(contains(msg, b) && contains(msg, a) && contains(msg, key) && contains(msg, "differs")) << key << ": " << msg;
  }
}

TEST(MergeChecks, RefusesAnotherResolution) {
  const std::string a = write_part("res_a.exr", {.first = 0, .last = 4});
  const std::string b = write_part("res_b.exr", {.first = 4, .last = 8, .full_height = 9});
  const std::string msg = merge_error({a, b});
  EXPECT_TRUE(contains(msg, b) && contains(msg, a) && contains(msg, "resolution 16x9")) << msg;
}

TEST(MergeChecks, RefusesDuplicates) {
  const std::string a = write_part("dup_a.exr", {.first = 0, .last = 4});
  const std::string b = write_part("dup_b.exr", {.first = 4, .last = 8});
  const std::string a2 = write_part("dup_a2.exr", {.first = 0, .last = 4});  // a re-run written elsewhere
  std::string msg = merge_error({a, b, a2});
  EXPECT_TRUE(contains(msg, a2 + ": duplicates " + a)) << msg;
  msg = merge_error({a, b, a});  // one file given twice
  EXPECT_TRUE(contains(msg, "duplicates " + a)) << msg;
}

TEST(MergeChecks, RefusesOverlaps) {
  // Sample ranges that overlap on the whole frame.
  const std::string a = write_part("ov_a.exr", {.first = 0, .last = 5});
  const std::string b = write_part("ov_b.exr", {.first = 4, .last = 8});
  std::string msg = merge_error({a, b});
  EXPECT_TRUE(contains(msg, b + ": overlaps " + a) && contains(msg, "samples 4:5")) << msg;
  // Crops that overlap in rows 3..4 with the same samples.
  const std::string top = write_part("ov_top.exr", {.y0 = 0, .y1 = 5});
  const std::string bottom = write_part("ov_bottom.exr", {.y0 = 3, .y1 = 8});
  msg = merge_error({top, bottom});
  EXPECT_TRUE(contains(msg, bottom + ": overlaps " + top) && contains(msg, "pixels 0,16,3,5")) << msg;
  // Overlapping crops with disjoint samples are fine.
  const std::string lo = write_part("ov_lo.exr", {.y0 = 0, .y1 = 5, .first = 0, .last = 4});
  const std::string hi = write_part("ov_hi.exr", {.y0 = 3, .y1 = 8, .first = 4, .last = 8});
  EXPECT_NO_THROW(merge_parts({lo, hi}));
}

TEST(MergeChecks, RefusesInterruptedParts) {
  const std::string a = write_part("int_a.exr", {.first = 0, .last = 4});
  const std::string b = write_part("int_b.exr", {.first = 4, .last = 8, .overrides = {{"kiln:incomplete", "true"}}});
  const std::string msg = merge_error({a, b});
  EXPECT_TRUE(contains(msg, b) && contains(msg, "interrupted") && contains(msg, "4:8")) << msg;
}

TEST(MergeChecks, RefusesPartsWithoutIdentity) {
  const std::string a = write_part("old_a.exr", {.first = 0, .last = 4});
  const std::string b = write_part("old_b.exr", {.first = 4, .last = 8, .overrides = {{"kiln:scene_hash", ""}}});
  std::string msg = merge_error({a, b});
  EXPECT_TRUE(contains(msg, b) && contains(msg, "no kiln:scene_hash")) << msg;
  const std::string c = write_part("old_c.exr", {.first = 4, .last = 8, .overrides = {{"kiln:spp_first", "x4"}}});
  msg = merge_error({a, c});
  EXPECT_TRUE(contains(msg, c) && contains(msg, "'x4'")) << msg;
  const std::string d = write_part("old_d.exr", {.first = 4, .last = 8, .overrides = {{"kiln:spp_last", "9"}}});
  msg = merge_error({a, d});
  EXPECT_TRUE(contains(msg, d) && contains(msg, "beyond the frame's 8 spp")) << msg;
}

TEST(MergeChecks, ReportsMissingSampleRanges) {
  // An spp split of 4 with the third range missing: one gap over the whole frame.
  const std::string s0 = write_part("gap_s0.exr", {.first = 0, .last = 2});
  const std::string s1 = write_part("gap_s1.exr", {.first = 2, .last = 4});
  const std::string s3 = write_part("gap_s3.exr", {.first = 6, .last = 8});
  MergeResult r = merge_parts({s0, s1, s3});
  ASSERT_EQ(r.missing.size(), 1u);
  EXPECT_EQ(r.missing[0].to_args(), "--crop 0,16,0,8 --spp-range 4:6");
  // A band split with the middle band missing, and the last band missing its last samples.
  const std::string b0 = write_part("gap_b0.exr", {.y0 = 0, .y1 = 3});
  const std::string b2 = write_part("gap_b2.exr", {.y0 = 6, .y1 = 8, .first = 0, .last = 5});
  r = merge_parts({b2, b0});
  ASSERT_EQ(r.missing.size(), 2u);
  EXPECT_EQ(r.missing[0].to_args(), "--crop 0,16,3,6 --spp-range 0:8");
  EXPECT_EQ(r.missing[1].to_args(), "--crop 0,16,6,8 --spp-range 5:8");
  // Complete parts report nothing.
  const std::string s2 = write_part("gap_s2.exr", {.first = 4, .last = 6});
  EXPECT_TRUE(merge_parts({s0, s1, s2, s3}).complete());
}

int run_kiln(const std::string& args, std::string& output) {
  FILE* p = popen((std::string(KILN_BINARY) + " " + args + " 2>&1").c_str(), "r");
  if (!p) return -1;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), int(buf.size()), p)) output += buf.data();
  const int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(MergeChecks, CliRefusesWithExitTwoAndNoOutput) {
  const std::string a = write_part("cli_a.exr", {.first = 0, .last = 4});
  const std::string b = write_part("cli_b.exr", {.first = 4, .last = 8, .overrides = {{"kiln:seed", "5"}}});
  const std::string out = tmp_dir("merge_checks") + "/cli_out.exr";
  fs::remove(out);
  std::string output;
  EXPECT_EQ(run_kiln("merge " + a + " " + b + " -o " + out, output), 2);
  EXPECT_TRUE(contains(output, b) && contains(output, a) && contains(output, "seed")) << output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(MergeChecks, CliMarksMissingRangesInTheOutput) {
  const std::string a = write_part("clim_a.exr", {.first = 0, .last = 4});
  const std::string out = tmp_dir("merge_checks") + "/clim_out.exr";
  std::string output;
  EXPECT_EQ(run_kiln("merge " + a + " -o " + out, output), 0);
  EXPECT_TRUE(contains(output, "missing samples 4:8 of 8 in pixels 0,16,0,8")) << output;
  const ExrFile f = read_exr(out);
  EXPECT_EQ(f.find("kiln:incomplete"), "true");
  EXPECT_EQ(f.find("kiln:missing"), "0,16,0,8 4:8");
  EXPECT_EQ(f.find("kiln:scene_hash"), "0123456789abcdef");
}

// The fingerprint covers the files the scene references, not only the scene file, and not their paths.
TEST(SceneFingerprint, CoversReferencedFilesNotPaths) {
  const std::string dir = tmp_dir("fingerprint");
  for (const char* sub : {"a", "b", "c"}) {
    fs::create_directories(dir + "/" + sub + "/killeroo");
    fs::copy_file(std::string(KILN_SOURCE_DIR) + "/scenes/killeroo_path.xml", dir + "/" + sub + "/scene.xml",
                  fs::copy_options::overwrite_existing);
    fs::copy_file(std::string(KILN_SOURCE_DIR) + "/scenes/killeroo/killeroo.ply", dir + "/" + sub + "/killeroo/killeroo.ply",
                  fs::copy_options::overwrite_existing);
  }
  // c's mesh differs in one byte of its header comment: same geometry, other bytes.
  {
    std::fstream f(dir + "/c/killeroo/killeroo.ply", std::ios::in | std::ios::out | std::ios::binary);
    std::string head(200, '\0');
    f.read(head.data(), std::streamsize(head.size()));
    const size_t at = head.find("killeroo control");
    ASSERT_NE(at, std::string::npos);
    f.seekp(std::streamoff(at));
    f.put('K');
  }
  SceneFingerprint fa, fb, fc;
  load_scene_fingerprinted(dir + "/a/scene.xml", {}, fa);
  load_scene_fingerprinted(dir + "/b/scene.xml", {}, fb);
  load_scene_fingerprinted(dir + "/c/scene.xml", {}, fc);
  EXPECT_EQ(fa.files, 2u);
  EXPECT_EQ(fa.hash.size(), 16u);
  EXPECT_EQ(fa.hash, fb.hash) << "the same files at another path";
  EXPECT_NE(fa.hash, fc.hash) << "a changed referenced mesh";
}

}  // namespace
}  // namespace kiln::test
