#include "renderer/image_io.h"

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>

#include "core/error.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

// Same folder (so rename is atomic), same extension (OIIO picks the format from it), unique per process.
std::string temp_name(const std::string& path) {
  const fs::path p(path);
  std::string name(".");  // built by appending: GCC 12 flags "." + string with a false -Wrestrict
  name.append(p.stem().string()).append(".tmp").append(std::to_string(::getpid())).append(p.extension().string());
  return (p.parent_path() / name).string();
}

void commit(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(path, "", "cannot move the finished image into place");
  }
}

void write_with_oiio(const std::string& path, const OIIO::ImageSpec& spec, const void* data) {
  if (!fs::path(path).parent_path().empty()) fs::create_directories(fs::path(path).parent_path());
  const std::string tmp = temp_name(path);
  auto out = OIIO::ImageOutput::create(tmp);
  if (!out) throw Error(path, "", "no image writer for this extension");
  if (!out->open(tmp, spec) || !out->write_image(spec.format, data) || !out->close()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw Error(path, "", "cannot write image: " + out->geterror());
  }
  commit(tmp, path);
}

// Every channel of the first subimage as float, interleaved; returns the file's spec.
OIIO::ImageSpec read_float_pixels(const std::string& path, std::vector<float>& data) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path, "", "cannot open image: " + OIIO::geterror());
  const OIIO::ImageSpec spec = in->spec();
  data.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
    throw Error(path, "", "cannot read image: " + in->geterror());
  in->close();
  return spec;
}

}  // namespace

void write_exr(const std::string& path, const Image& rgb, const std::vector<AovLayer>& aovs, const Metadata& meta,
               const std::optional<DataWindow>& window) {
  size_t nch = 3;
  for (const AovLayer& a : aovs) nch += a.channels.size();
  OIIO::ImageSpec spec(rgb.width(), rgb.height(), int(nch), OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B"};
  for (const AovLayer& a : aovs)
    for (const std::string& c : a.channels) spec.channelnames.push_back(c);
  spec.attribute("compression", "zip");
  if (window) {
    spec.x = window->x;
    spec.y = window->y;
    spec.full_x = spec.full_y = 0;
    spec.full_width = window->full_width;
    spec.full_height = window->full_height;
  }
  for (const auto& [k, v] : meta) spec.attribute(k, v);
  const size_t npx = size_t(rgb.width()) * size_t(rgb.height());
  std::vector<float> data(npx * nch);
  for (size_t i = 0; i < npx; ++i) {
    float* d = &data[i * nch];
    const Rgb& c = rgb.pixels()[i];
    d[0] = c.r;
    d[1] = c.g;
    d[2] = c.b;
    size_t k = 3;
    for (const AovLayer& a : aovs)
      for (size_t j = 0; j < a.channels.size(); ++j) d[k++] = a.data[i * a.channels.size() + j];
  }
  write_with_oiio(path, spec, data.data());
}

void write_png(const std::string& path, const std::vector<uint8_t>& rgb8, int width, int height) {
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  write_with_oiio(path, spec, rgb8.data());
}

ExrFile read_exr(const std::string& path) {
  std::vector<float> data;
  const OIIO::ImageSpec spec = read_float_pixels(path, data);
  const int nch = spec.nchannels;
  int ir = -1, ig = -1, ib = -1;
  for (int c = 0; c < nch; ++c) {
    const std::string& n = spec.channelnames[size_t(c)];
    if (n == "R") ir = c;
    if (n == "G") ig = c;
    if (n == "B") ib = c;
  }
  if (ir < 0 || ig < 0 || ib < 0) throw Error(path, "", "image has no R, G, B channels");
  ExrFile f;
  f.rgb = Image(spec.width, spec.height);
  const size_t npx = size_t(spec.width) * size_t(spec.height);
  for (size_t i = 0; i < npx; ++i) {
    const float* d = &data[i * size_t(nch)];
    f.rgb.pixels()[i] = Rgb(d[ir], d[ig], d[ib]);
  }
  for (int c = 0; c < nch; ++c) {
    if (c == ir || c == ig || c == ib) continue;
    AovLayer a;
    a.channels = {spec.channelnames[size_t(c)]};
    a.data.resize(npx);
    for (size_t i = 0; i < npx; ++i) a.data[i] = data[i * size_t(nch) + size_t(c)];
    f.aovs.push_back(std::move(a));
  }
  for (const auto& p : spec.extra_attribs) f.meta.emplace_back(p.name().string(), p.get_string());
  f.window = DataWindow{spec.x, spec.y, spec.full_width, spec.full_height};
  return f;
}

std::string find_meta(const Metadata& meta, const std::string& key) {
  for (const auto& [k, v] : meta)
    if (k == key) return v;
  return {};
}

ExrHeader read_exr_header(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path, "", "cannot open image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  ExrHeader h;
  for (const auto& p : spec.extra_attribs) h.meta.emplace_back(p.name().string(), p.get_string());
  h.window = DataWindow{spec.x, spec.y, spec.full_width, spec.full_height};
  h.width = spec.width;
  h.height = spec.height;
  in->close();
  return h;
}

Image read_image(const std::string& path) {
  std::vector<float> data;
  const OIIO::ImageSpec spec = read_float_pixels(path, data);
  const int nch = spec.nchannels;
  Image img(spec.width, spec.height);
  for (size_t i = 0; i < img.pixels().size(); ++i) {
    const float* d = &data[i * size_t(nch)];
    img.pixels()[i] = nch >= 3 ? Rgb(d[0], d[1], d[2]) : Rgb(d[0]);
  }
  return img;
}

}  // namespace kiln
