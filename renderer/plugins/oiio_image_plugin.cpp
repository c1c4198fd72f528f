// Kiln's OpenImageIO plugin (renderer/image_plugin.h explains why it is a separately loaded module). Built as
// kiln_oiio_plugin.so; the only Kiln code that links OpenImageIO.
#include <OpenImageIO/imageio.h>

#include "renderer/image_plugin.h"

namespace kiln {
namespace {

bool read_rgb(const std::string& path, std::vector<float>& rgb, int& width, int& height, std::string& error) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    error = OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  const int nch = spec.nchannels;
  std::vector<float> data(size_t(spec.width) * size_t(spec.height) * size_t(nch));
  if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, data.data())) {
    error = in->geterror();
    return false;
  }
  width = spec.width;
  height = spec.height;
  const size_t npx = size_t(width) * size_t(height);
  rgb.resize(npx * 3);
  for (size_t i = 0; i < npx; ++i)
    for (size_t c = 0; c < 3; ++c) rgb[3 * i + c] = data[i * size_t(nch) + (nch >= 3 ? c : 0)];
  return true;
}

const ImagePluginApi kApi{kImagePluginAbiVersion, &read_rgb};

}  // namespace
}  // namespace kiln

extern "C" __attribute__((visibility("default"))) const kiln::ImagePluginApi* kiln_image_plugin_v1() {
  return &kiln::kApi;
}
