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
#include "support/shared_data.h"

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
                {"kiln:scene_files", "00000000000000aa scene.xml\n00000000000000bb textures/earth.jpg"},
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

// A part of another scene names the first file whose hash differs, from the parts' kiln:scene_files.
TEST(MergeChecks, NamesTheFirstSceneFileThatDiffers) {
  const std::string a = write_part("file_a.exr", {.first = 0, .last = 4});
  const std::string b = write_part(
      "file_b.exr", {.first = 4, .last = 8,
                     .overrides = {{"kiln:scene_hash", "fedcba9876543210"},
                                   {"kiln:scene_files", "00000000000000aa scene.xml\n00000000000000cc textures/earth.jpg"}}});
  const std::string msg = merge_error({a, b});
  EXPECT_TRUE(contains(msg, b + ": scene") && contains(msg, "differs from " + a) &&
              contains(msg, "first scene file that differs: textures/earth.jpg (hash 00000000000000cc vs 00000000000000bb)"))
      << msg;
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

// Runs `kiln ARGS` (or, with kiln = false, the command line ARGS) and collects stdout and stderr.
int run_kiln(const std::string& args, std::string& output, bool kiln = true) {
  FILE* p = popen(((kiln ? std::string(KILN_BINARY) + " " : std::string()) + args + " 2>&1").c_str(), "r");
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
  ASSERT_EQ(fa.files.size(), 2u);
  EXPECT_EQ(fa.files[0].name, "scene.xml");
  EXPECT_EQ(fa.files[1].name, "killeroo/killeroo.ply");
  EXPECT_EQ(fa.hash.size(), 16u);
  EXPECT_EQ(fa.hash, fb.hash) << "the same files at another path";
  EXPECT_NE(fa.hash, fc.hash) << "a changed referenced mesh";
  EXPECT_EQ(first_file_difference(fc.files, fa.files).value_or(""),
            "killeroo/killeroo.ply (hash " + fc.files[1].hash + " vs " + fa.files[1].hash + ")");
  EXPECT_FALSE(first_file_difference(fa.files, fb.files));
  // The metadata form reads back as written.
  const auto back = parse_scene_files_metadata(scene_files_metadata(fa));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].name, fa.files[1].name);
  EXPECT_EQ(back[1].hash, fa.files[1].hash);
  EXPECT_TRUE(parse_scene_files_metadata("2").empty()) << "an older kiln's file count";
}

// Files the loader does not read itself (SceneDesc::external_files: texture images of both XML forms, the background
// image, environment maps) follow the files it read, in the loader's order, once each; a changed byte in any of
// them changes the identity and is named.
TEST(SceneFingerprint, CoversTextureImagesAndEnvironmentMaps) {
  const std::string dir = tmp_dir("fingerprint_external");
  const auto write = [&](const std::string& name, const std::string& bytes) {
    fs::create_directories(fs::path(dir + "/" + name).parent_path());
    std::ofstream(dir + "/" + name, std::ios::binary) << bytes;
  };
  // The loader does not decode images: any bytes stand in for them here.
  for (const char* f : {"textures/sky.jpg", "textures/earth.jpg", "textures/bump.png", "env/pisa.exr"}) write(f, f);
  write("scene.xml", R"(<Scene>
  <BackgroundTexture>textures/sky.jpg</BackgroundTexture>
  <Cameras><Camera id="1"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
    <NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>8 8</ImageResolution>
    <ImageName>out.png</ImageName></Camera></Cameras>
  <Lights><SphericalDirectionalLight id="1"><ImageId>7</ImageId></SphericalDirectionalLight></Lights>
  <Materials><Material id="1"><DiffuseReflectance>1 1 1</DiffuseReflectance></Material></Materials>
  <Textures>
    <Images><Image id="5">textures/bump.png</Image><Image id="7">env/pisa.exr</Image></Images>
    <Texture id="1"><ImageName>textures/earth.jpg</ImageName></Texture>
    <Texture id="2"><ImageName>textures/earth.jpg</ImageName><DecalMode>blend_kd</DecalMode></Texture>
    <TextureMap id="3" type="image"><ImageId>5</ImageId><DecalMode>bump_normal</DecalMode></TextureMap>
  </Textures>
  <VertexData>0 0 -2 1 0 -2 0 1 -2</VertexData>
  <Objects><Mesh id="1"><Material>1</Material><Textures>1 3</Textures><Faces>1 2 3</Faces></Mesh></Objects>
</Scene>)");
  SceneFingerprint before;
  load_scene_fingerprinted(dir + "/scene.xml", {}, before);
  std::vector<std::string> names;
  for (const FingerprintedFile& f : before.files) names.push_back(f.name);
  EXPECT_EQ(names, (std::vector<std::string>{"scene.xml", "textures/sky.jpg", "textures/earth.jpg", "textures/bump.png",
                                             "env/pisa.exr"}));
  for (const char* f : {"textures/sky.jpg", "textures/earth.jpg", "textures/bump.png", "env/pisa.exr"}) {
    SCOPED_TRACE(f);
    write(f, std::string(f) + " changed");
    SceneFingerprint after;
    load_scene_fingerprinted(dir + "/scene.xml", {}, after);
    EXPECT_NE(after.hash, before.hash);
    EXPECT_TRUE(contains(first_file_difference(after.files, before.files).value_or(""), std::string(f) + " (hash"));
    write(f, f);
  }
  SceneFingerprint again;
  load_scene_fingerprinted(dir + "/scene.xml", {}, again);
  EXPECT_EQ(again.hash, before.hash);
}

// A pbrt-v4 scene's spectrum files (.spd, read by the loader itself) are part of its identity: listed after the
// scene file, relative to it, and a changed value changes the identity and is named.
TEST(SceneFingerprint, CoversPbrtSpectrumFiles) {
  const std::string dir = tmp_dir("fingerprint_spd");
  fs::create_directories(dir + "/spectra");
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name, std::ios::binary) << text;
  };
  write("spectra/flat.spd", "300 0.4\n900 0.4\n");
  write("scene.pbrt",
        "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 8 "
        "\"integer yresolution\" 8\nWorldBegin\nMaterial \"diffuse\" \"spectrum reflectance\" \"spectra/flat.spd\"\n"
        "Shape \"sphere\"\n");
  SceneFingerprint before;
  load_scene_fingerprinted(dir + "/scene.pbrt", {}, before);
  std::vector<std::string> names;
  for (const FingerprintedFile& f : before.files) names.push_back(f.name);
  EXPECT_EQ(names, (std::vector<std::string>{"scene.pbrt", "spectra/flat.spd"}));
  write("spectra/flat.spd", "300 0.5\n900 0.5\n");
  SceneFingerprint after;
  load_scene_fingerprinted(dir + "/scene.pbrt", {}, after);
  EXPECT_NE(after.hash, before.hash);
  EXPECT_TRUE(contains(first_file_difference(after.files, before.files).value_or(""), "spectra/flat.spd (hash"));
}

// The CENG795 scene hw4_2019/sphere_texture_replace_bilinear.xml split into two sample ranges, its earth.jpg
// inverted between them: `kiln merge` refuses the parts (exit 2, no output), naming both and the texture. With the
// texture restored, the same parts merge.
class SceneIdentity : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string shared = shared_dir() + "/scenes/ceng795/regression/hw4_2019";
    KILN_NEED_SHARED_PATH(shared + "/sphere_texture_replace_bilinear.xml");
    // One folder per test: ctest runs the fixture's tests as concurrent processes, and each empties its folder.
    dir_ = tmp_dir(std::string("scene_identity_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ + "/scene/textures");
    fs::copy_file(shared + "/sphere_texture_replace_bilinear.xml", scene());
    fs::copy_file(shared + "/textures/earth.jpg", earth());
    fs::permissions(earth(), fs::perms::owner_write, fs::perm_options::add);
  }
  std::string scene() const { return dir_ + "/scene/sphere_texture_replace_bilinear.xml"; }
  std::string earth() const { return dir_ + "/scene/textures/earth.jpg"; }
  // Renders samples `range` of an 8-spp frame, cropped around the textured sphere; returns the part's path.
  std::string render_part(const std::string& range, const std::string& out) const {
    std::string log;
    EXPECT_EQ(run_kiln("render " + scene() + " -q --spp 8 --spp-range " + range + " --crop 370,430,370,430 -o " +
                           dir_ + "/" + out, log), 0) << log;
    return dir_ + "/" + out + "/sphere_texture_replace_bilinear.exr";
  }
  std::string dir_;
};

TEST_F(SceneIdentity, MergeRefusesPartsRenderedWithAnotherTexture) {
  const std::string original = dir_ + "/earth_original.jpg";
  fs::copy_file(earth(), original);
  const std::string a = render_part("0:4", "part_a");
  std::string log;
  ASSERT_EQ(run_kiln("oiiotool " + earth() + " --invert -o " + earth(), log, false), 0)
      << "oiiotool (openimageio-tools, .ci/install-deps.sh) inverts the texture: " << log;
  const std::string b = render_part("4:8", "part_b");
  EXPECT_FALSE(read_exr(a).rgb.pixels() == read_exr(b).rgb.pixels()) << "the inverted texture shows";
  const std::string out = dir_ + "/merged.exr";
  log.clear();
  EXPECT_EQ(run_kiln("merge " + a + " " + b + " -o " + out, log), 2) << log;
  EXPECT_TRUE(contains(log, b + ": scene (hash of its files) differs from " + a)) << log;
  EXPECT_TRUE(contains(log, "first scene file that differs: textures/earth.jpg (hash ")) << log;
  EXPECT_FALSE(fs::exists(out));

  fs::copy_file(original, earth(), fs::copy_options::overwrite_existing);
  const std::string b2 = render_part("4:8", "part_b2");
  log.clear();
  EXPECT_EQ(run_kiln("merge " + a + " " + b2 + " -o " + out, log), 0) << log;
  EXPECT_TRUE(fs::exists(out));
}

// `kiln info` prints the identity and every file it covers: the scene file and its texture.
TEST_F(SceneIdentity, InfoListsTheFilesItCovers) {
  std::string log;
  ASSERT_EQ(run_kiln("info " + scene(), log), 0) << log;
  SceneFingerprint f;
  load_scene_fingerprinted(scene(), {}, f);
  EXPECT_TRUE(contains(log, "identity: " + f.hash + " (2 files, ")) << log;
  ASSERT_EQ(f.files.size(), 2u);
  for (const FingerprintedFile& file : f.files)
    EXPECT_TRUE(contains(log, file.hash) && contains(log, "  " + file.name + "\n")) << file.name << "\n" << log;
  EXPECT_EQ(f.files[1].name, "textures/earth.jpg");
  EXPECT_EQ(f.files[1].bytes, fs::file_size(earth()));
}

}  // namespace
}  // namespace kiln::test
