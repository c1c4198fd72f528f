// The image formats behind renderer/image_io/image_io.h, one file each: EXR through OpenEXR (exr_file.cpp), PNG through
// libpng (png_file.cpp). Both libraries load in a few milliseconds; every other format goes through the
// OpenImageIO plugin (image_plugin.h), which is loaded only when such a file is read. Writers write to the path
// they are given (image_io.cpp gives them a temporary name and renames the finished file into place) and throw
// kiln::Error naming `shown_path`.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "renderer/image_io/image_io.h"

namespace kiln::detail {

void write_exr_file(const std::string& path, const std::string& shown_path, const Image& rgb,
                    const std::vector<AovLayer>& aovs, const Metadata& meta, const std::optional<DataWindow>& window);
ExrFile read_exr_file(const std::string& path);
ExrHeader read_exr_header_file(const std::string& path);  // the header only: no pixel is read

void write_png_file(const std::string& path, const std::string& shown_path, const std::vector<uint8_t>& rgb8,
                    int width, int height);
// 8- and 16-bit PNGs of any colour type as RGB in [0, 1] (value / 255 or / 65535, no transfer curve applied).
Image read_png_file(const std::string& path);

}  // namespace kiln::detail
