#include "renderer/image_io/image_io.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "renderer/image_io/image_formats.h"
#include "renderer/image_io/image_plugin.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

// Same folder (so rename is atomic), same extension, unique per process.
std::string temp_name(const std::string& path) {
  const fs::path p(path);
  std::string name(".");  // built by appending: GCC 12 flags "." + string with a false -Wrestrict
  name.append(p.stem().string()).append(".tmp").append(std::to_string(::getpid())).append(p.extension().string());
  return (p.parent_path() / name).string();
}

// Writes through `write(tmp)` to a temporary file, then renames it into place; removes it on failure.
template <class WriteFn>
void write_atomically(const std::string& path, WriteFn&& write) {
  if (!fs::path(path).parent_path().empty()) fs::create_directories(fs::path(path).parent_path());
  const std::string tmp = temp_name(path);
  std::error_code ec;
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(path, "", "cannot move the finished image into place");
  }
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

void write_exr(const std::string& path, const Image& rgb, const std::vector<AovLayer>& aovs, const Metadata& meta,
               const std::optional<DataWindow>& window) {
  write_atomically(path, [&](const std::string& tmp) { detail::write_exr_file(tmp, path, rgb, aovs, meta, window); });
}

void write_png(const std::string& path, const std::vector<uint8_t>& rgb8, int width, int height) {
  write_atomically(path, [&](const std::string& tmp) { detail::write_png_file(tmp, path, rgb8, width, height); });
}

ExrFile read_exr(const std::string& path) { return detail::read_exr_file(path); }

std::string find_meta(const Metadata& meta, const std::string& key) {
  for (const auto& [k, v] : meta)
    if (k == key) return v;
  return {};
}

ExrHeader read_exr_header(const std::string& path) { return detail::read_exr_header_file(path); }

Image read_image(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".exr") return read_exr(path).rgb;
  if (ext == ".png") return detail::read_png_file(path);
  std::vector<float> rgb;
  int width = 0, height = 0;
  std::string error;
  if (!image_plugin(path).read_rgb(path, rgb, width, height, error)) throw Error(path, "", "cannot read image: " + error);
  Image img(width, height);
  for (size_t i = 0; i < img.pixels().size(); ++i) img.pixels()[i] = Rgb(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
  return img;
}

bool is_float_image_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

}  // namespace kiln
