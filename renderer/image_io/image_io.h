// EXR (OpenEXR) and PNG (libpng) output and input; other formats are read through the OpenImageIO plugin
// (renderer/image_io/image_plugin.h), loaded only when needed. Every file is written to a temporary name in the target
// folder and renamed into place, so a crash or an interrupt never leaves a half-written image.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace kiln {

// An extra image layer written next to R,G,B (e.g. Albedo.R/G/B, N.X/Y/Z, Z).
struct AovLayer {
  std::vector<std::string> channels;  // full channel names
  std::vector<float> data;            // interleaved, channels.size() floats per pixel
};

using Metadata = std::vector<std::pair<std::string, std::string>>;

// Where a cropped image sits in the full frame (EXR data window inside the display window).
struct DataWindow {
  int x = 0, y = 0;                  // origin of the data window
  int full_width = 0, full_height = 0;
};

// Linear float32 (never half: values above 65504 must survive) with string metadata attributes.
void write_exr(const std::string& path, const Image& rgb, const std::vector<AovLayer>& aovs, const Metadata& meta,
               const std::optional<DataWindow>& window = std::nullopt);
void write_png(const std::string& path, const std::vector<uint8_t>& rgb8, int width, int height);

// The value of key in meta; empty when absent.
std::string find_meta(const Metadata& meta, const std::string& key);

struct ExrFile {
  Image rgb;
  std::vector<AovLayer> aovs;  // every channel other than R, G, B (one layer per channel here)
  Metadata meta;        // the file's string attributes (Kiln writes its metadata as strings)
  DataWindow window;  // the data window (x, y) and the full frame size
  std::string find(const std::string& key) const { return find_meta(meta, key); }
};
// Throws kiln::Error when the file cannot be read or has no R,G,B channels.
ExrFile read_exr(const std::string& path);

// An image's metadata, data window and size, without its pixels.
struct ExrHeader {
  Metadata meta;
  DataWindow window;
  int width = 0, height = 0;  // of the data window
  std::string find(const std::string& key) const { return find_meta(meta, key); }
};
// Throws kiln::Error when the file cannot be opened as an image.
ExrHeader read_exr_header(const std::string& path);
// EXR, PNG (float RGB, stored value / 255 or / 65535, no transfer curve), or any format OpenImageIO reads (through
// the plugin). Throws kiln::Error naming the file when it cannot be read.
Image read_image(const std::string& path);
// True for the float formats (EXR, HDR, PFM), which hold linear values; the others (PNG, JPEG, TGA, ...) store
// sRGB-encoded 8- or 16-bit values, which pbrt-v4 decodes when it reads an image for a light.
bool is_float_image_format(const std::string& path);

}  // namespace kiln
