// Image input/output without OpenImageIO at start-up: EXR (OpenEXR) and PNG (libpng) are read and written directly,
// other formats go through the OpenImageIO plugin, and `kiln` starts, reports and fails without loading OpenImageIO
// (which would add ~260 shared libraries and half a second to every start).
#include <gtest/gtest.h>
#include <png.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>

#include "core/error.h"
#include "renderer/render_util.h"
#include "renderer/image_io/image_io.h"

namespace kiln::test {
namespace {

// stdout + stderr of a shell command, and its exit code.
std::pair<int, std::string> run_shell(const std::string& cmd) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return {-1, out};
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), int(buf.size()), p)) out += buf.data();
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// Why: every byte value of an 8-bit PNG comes back as value / 255, the convention the course-reference comparisons
// use (no transfer curve is applied on reading).
TEST(ImageIo, PngRoundTripKeepsEveryByte) {
  constexpr int kW = 16, kH = 16;
  std::vector<uint8_t> rgb(size_t(kW * kH * 3));
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t((i * 7 + i / 3) % 256);
  const std::string path = tmp_dir("image_io") + "/bytes.png";
  write_png(path, rgb, kW, kH);
  const Image back = read_image(path);
  ASSERT_EQ(back.width(), kW);
  ASSERT_EQ(back.height(), kH);
  for (size_t i = 0; i < size_t(kW * kH); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(back.pixels()[i][c], float(rgb[3 * i + size_t(c)]) / 255.0f) << "pixel " << i << " channel " << c;
}

// Why: 16-bit and grey PNGs (other tools' references) are widened to RGB with value / 65535, not re-encoded.
TEST(ImageIo, Png16BitGreyIsReadAsStored) {
  constexpr int kW = 5, kH = 3;
  std::vector<uint16_t> grey(size_t(kW * kH));
  for (size_t i = 0; i < grey.size(); ++i) grey[i] = uint16_t(i * 4321 + 17);
  const std::string path = tmp_dir("image_io") + "/grey16.png";
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = kW;
  image.height = kH;
  image.format = PNG_FORMAT_LINEAR_Y;  // 16-bit grey, written as given
  ASSERT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, grey.data(), 0, nullptr)) << image.message;
  const Image back = read_image(path);
  ASSERT_EQ(back.width(), kW);
  for (size_t i = 0; i < grey.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(back.pixels()[i][c], float(grey[i]) / 65535.0f) << "pixel " << i;
}

// Why: a cropped render is an EXR whose data window sits inside the full frame; `kiln merge` places parts by it.
TEST(ImageIo, ExrDataWindowAndMetadataRoundTrip) {
  Image img(3, 2);
  for (size_t i = 0; i < img.pixels().size(); ++i) img.pixels()[i] = Rgb(float(i), 0.5f * float(i), -1.0f);
  const std::string path = tmp_dir("image_io") + "/window.exr";
  write_exr(path, img, {}, {{"kiln:spp_first", "4"}, {"kiln:spp_last", "9"}}, DataWindow{5, 7, 20, 10});
  const ExrFile f = read_exr(path);
  EXPECT_EQ(f.window.x, 5);
  EXPECT_EQ(f.window.y, 7);
  EXPECT_EQ(f.window.full_width, 20);
  EXPECT_EQ(f.window.full_height, 10);
  EXPECT_EQ(f.find("kiln:spp_first"), "4");
  EXPECT_EQ(f.find("kiln:spp_last"), "9");
  ASSERT_EQ(f.rgb.width(), 3);
  ASSERT_EQ(f.rgb.height(), 2);
  for (size_t i = 0; i < img.pixels().size(); ++i) EXPECT_EQ(f.rgb.pixels()[i].g, img.pixels()[i].g) << i;
}

// Why: formats other than EXR and PNG are read by OpenImageIO in the plugin. An uncompressed 24-bit TGA, written
// here byte by byte, must come back exactly.
TEST(ImageIo, OtherFormatsAreReadThroughTheOpenImageIOPlugin) {
  constexpr int kW = 4, kH = 2;
  const std::string path = tmp_dir("image_io") + "/tiny.tga";
  std::array<uint8_t, 18> header{};
  header[2] = 2;  // uncompressed true colour
  header[12] = kW;
  header[14] = kH;
  header[16] = 24;    // bits per pixel
  header[17] = 0x20;  // rows stored top to bottom
  std::vector<uint8_t> bgr(size_t(kW * kH * 3));
  for (size_t i = 0; i < bgr.size(); ++i) bgr[i] = uint8_t(i * 29 + 3);
  {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(header.data()), header.size());
    f.write(reinterpret_cast<const char*>(bgr.data()), std::streamsize(bgr.size()));
  }
  const Image img = read_image(path);
  ASSERT_EQ(img.width(), kW);
  ASSERT_EQ(img.height(), kH);
  // OpenImageIO converts by multiplying with 1/255: within an ulp of value / 255.
  for (size_t i = 0; i < size_t(kW * kH); ++i) {
    EXPECT_NEAR(img.pixels()[i].r, float(bgr[3 * i + 2]) / 255.0f, 1e-6f) << i;
    EXPECT_NEAR(img.pixels()[i].g, float(bgr[3 * i + 1]) / 255.0f, 1e-6f) << i;
    EXPECT_NEAR(img.pixels()[i].b, float(bgr[3 * i]) / 255.0f, 1e-6f) << i;
  }
}

// Why: an unreadable image is bad input: kiln::Error naming the file, for every reader.
TEST(ImageIo, UnreadableImagesNameTheFile) {
  const std::string dir = tmp_dir("image_io");
  for (const char* name : {"garbage.exr", "garbage.png", "garbage.jpg", "missing.png", "missing.tif"}) {
    const std::string path = dir + "/" + name;
    std::filesystem::remove(path);
    if (std::string(name).rfind("garbage", 0) == 0) std::ofstream(path) << "not an image at all";
    try {
      (void)read_image(path);
      ADD_FAILURE() << name << " was read";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

// Why: start-up. `kiln --version`, `kiln info`, a bad-input error and a render (EXR + PNG) must not load
// OpenImageIO: ld.so's LD_DEBUG=files log lists every object a process loads, including dlopen()ed ones.
TEST(ImageIo, KilnRunsWithoutLoadingOpenImageIO) {
  const std::string kiln = KILN_BINARY, scene = std::string(KILN_SOURCE_DIR) + "/scenes/default.xml";
  const std::string dir = tmp_dir("image_io_startup");
  const std::string bad = dir + "/bad.xml";
  std::ofstream(bad) << "<Scene><Cameras>";
  const std::vector<std::pair<std::string, int>> runs = {
      {kiln + " --version", 0},
      {kiln + " info " + scene, 0},
      {kiln + " info " + bad, kExitBadInput},
      {kiln + " render " + scene + " -q --spp 1 --crop 0,16,0,16 -o " + dir + "/out", 0}};
  for (const auto& [cmd, want_exit] : runs) {
    const auto [code, log] = run_shell("LD_DEBUG=files " + cmd);
    EXPECT_EQ(code, want_exit) << cmd << "\n" << log.substr(0, 2000);
    EXPECT_NE(log.find("libembree3"), std::string::npos) << "LD_DEBUG log not captured for: " << cmd;
    EXPECT_EQ(log.find("libOpenImageIO"), std::string::npos) << cmd << " loads OpenImageIO";
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/default.exr"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/default.png"));
}

}  // namespace
}  // namespace kiln::test
