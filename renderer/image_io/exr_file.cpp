// EXR through OpenEXR's C++ API: scanline float32 channels, ZIP compression, string attributes, data window.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <exception>
#include <string_view>

#include "core/error.h"
#include "renderer/image_io/image_formats.h"

namespace kiln::detail {
namespace {

Imath::Box2i box(int x, int y, int width, int height) {
  return Imath::Box2i(Imath::V2i(x, y), Imath::V2i(x + width - 1, y + height - 1));
}

}  // namespace

void write_exr_file(const std::string& path, const std::string& shown_path, const Image& rgb,
                    const std::vector<AovLayer>& aovs, const Metadata& meta, const std::optional<DataWindow>& window) {
  const int w = rgb.width(), h = rgb.height();
  const Imath::Box2i data = window ? box(window->x, window->y, w, h) : box(0, 0, w, h);
  const Imath::Box2i display = window ? box(0, 0, window->full_width, window->full_height) : data;
  // Planar float32 buffers, one per channel (R, G, B, then the AOV channels in order).
  std::vector<std::string> names = {"R", "G", "B"};
  for (const AovLayer& a : aovs) names.insert(names.end(), a.channels.begin(), a.channels.end());
  const size_t npx = size_t(w) * size_t(h);
  std::vector<std::vector<float>> planes(names.size(), std::vector<float>(npx));
  for (size_t i = 0; i < npx; ++i)
    for (int c = 0; c < 3; ++c) planes[size_t(c)][i] = rgb.pixels()[i][c];
  size_t plane = 3;
  for (const AovLayer& a : aovs)
    for (size_t j = 0; j < a.channels.size(); ++j, ++plane)
      for (size_t i = 0; i < npx; ++i) planes[plane][i] = a.data[i * a.channels.size() + j];
  try {
    Imf::Header header(display, data);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < names.size(); ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, planes[c].data(), data, sizeof(float),
                                           sizeof(float) * size_t(w)));
    }
    for (const auto& [k, v] : meta) header.insert(k, Imf::StringAttribute(v));
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(h);
  } catch (const std::exception& e) {
    throw Error(shown_path, "", std::string("cannot write EXR: ") + e.what());
  }
}

namespace {

Metadata string_attributes(const Imf::Header& header) {
  Metadata meta;
  for (auto it = header.begin(); it != header.end(); ++it)
    if (std::string_view(it.attribute().typeName()) == Imf::StringAttribute::staticTypeName())
      meta.emplace_back(it.name(), static_cast<const Imf::StringAttribute&>(it.attribute()).value());
  return meta;
}

DataWindow window_of(const Imath::Box2i& data, const Imath::Box2i& display) {
  return DataWindow{data.min.x - display.min.x, data.min.y - display.min.y, display.max.x - display.min.x + 1,
                    display.max.y - display.min.y + 1};
}

}  // namespace

ExrHeader read_exr_header_file(const std::string& path) {
  try {
    Imf::InputFile in(path.c_str());
    const Imf::Header& header = in.header();
    const Imath::Box2i data = header.dataWindow();
    ExrHeader h;
    h.meta = string_attributes(header);
    h.window = window_of(data, header.displayWindow());
    h.width = data.max.x - data.min.x + 1;
    h.height = data.max.y - data.min.y + 1;
    return h;
  } catch (const std::exception& e) {
    throw Error(path, "", std::string("cannot read EXR: ") + e.what());
  }
}

ExrFile read_exr_file(const std::string& path) {
  try {
    Imf::InputFile in(path.c_str());
    const Imf::Header& header = in.header();
    const Imath::Box2i data = header.dataWindow(), display = header.displayWindow();
    const int w = data.max.x - data.min.x + 1, h = data.max.y - data.min.y + 1;
    const size_t npx = size_t(w) * size_t(h);
    // Every channel is read as float (half and uint channels are converted by OpenEXR).
    std::vector<std::string> names;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) names.emplace_back(it.name());
    std::vector<std::vector<float>> planes(names.size(), std::vector<float>(npx));
    Imf::FrameBuffer fb;
    int ir = -1, ig = -1, ib = -1;
    for (size_t c = 0; c < names.size(); ++c) {
      fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, planes[c].data(), data, sizeof(float),
                                           sizeof(float) * size_t(w)));
      if (names[c] == "R") ir = int(c);
      if (names[c] == "G") ig = int(c);
      if (names[c] == "B") ib = int(c);
    }
    if (ir < 0 || ig < 0 || ib < 0) throw Error(path, "", "image has no R, G, B channels");
    in.setFrameBuffer(fb);
    in.readPixels(data.min.y, data.max.y);

    ExrFile f;
    f.rgb = Image(w, h);
    for (size_t i = 0; i < npx; ++i)
      f.rgb.pixels()[i] = Rgb(planes[size_t(ir)][i], planes[size_t(ig)][i], planes[size_t(ib)][i]);
    for (size_t c = 0; c < names.size(); ++c) {
      if (int(c) == ir || int(c) == ig || int(c) == ib) continue;
      f.aovs.push_back(AovLayer{{names[c]}, std::move(planes[c])});
    }
    f.meta = string_attributes(header);
    f.window = window_of(data, display);
    return f;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path, "", std::string("cannot read EXR: ") + e.what());
  }
}

}  // namespace kiln::detail
