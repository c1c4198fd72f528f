// Kiln's OpenImageIO plugin (renderer/image_io/image_plugin.h explains why it is a separately loaded module). Built as
// kiln_oiio_plugin.so; the only Kiln code that links OpenImageIO.
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <vector>

#include "renderer/image_io/image_plugin.h"

namespace kiln {
namespace {

// The reader is the one the file's extension names. OpenImageIO's open() would, on failure, go on to try every
// reader it has: the message then names the last format tried instead of the file's, and each reader's libraries
// set up their thread-local state in this process for nothing.
bool read_rgb(const std::string& path, std::vector<float>& rgb, int& width, int& height, std::string& error) {
  auto in = OIIO::ImageInput::create(path, /*do_open=*/false);
  if (!in) {
    error = OIIO::geterror();
    return false;
  }
  OIIO::ImageSpec opened;
  if (!in->open(path, opened)) {
    error = in->geterror();
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

// ---- textures ---------------------------------------------------------------------------------------------------

// A world's view of OpenImageIO's process-wide shared TextureSystem: the per-thread records it made and the files
// it opened, released when the world goes. Not a private system: OpenImageIO 2.4's TextureSystem::destroy deletes a
// private one through its base class (AddressSanitizer: new-delete-type-mismatch, 184 bytes allocated, 1 freed), so
// the object's own members are never destroyed; the shared one is owned by OpenImageIO and freed at exit. The
// per-thread records are created and destroyed here, not taken from get_perthread_info(): that thread-specific
// pointer outlives a destroyed cache on every thread but the one that destroys it (stale tiles, wrong texels).
struct System {
  OIIO::TextureSystem* ts = nullptr;
  std::mutex mutex;
  std::vector<OIIO::TextureSystem::Perthread*> thread_infos;
  std::vector<OIIO::ustring> files;
  OIIO::TextureSystem::Perthread* probe = nullptr;  // the record texture_open reads its test texel with
};

OIIO::TextureSystem* system_of(void* s) { return static_cast<System*>(s)->ts; }

void* texture_system_create(const TextureSystemOptions& o, std::string& error) {
  OIIO::TextureSystem* ts = OIIO::TextureSystem::create(true);
  if (!ts) {
    error = "OpenImageIO could not create a TextureSystem";
    return nullptr;
  }
  ts->attribute("max_memory_MB", o.max_memory_mb);
  ts->attribute("autotile", o.autotile);
  ts->attribute("automip", 1);  // files without MIP levels get them built in the cache (trilinear / filtered lookups)
  auto* s = new System;
  s->ts = ts;
  return s;
}

void texture_system_destroy(void* s) {
  if (!s) return;
  auto* sys = static_cast<System*>(s);
  for (OIIO::TextureSystem::Perthread* p : sys->thread_infos) sys->ts->destroy_thread_info(p);
  // A later world that opens the same path (rewritten in between) must read the file again, not this one's tiles.
  for (const OIIO::ustring& f : sys->files) sys->ts->invalidate(f, true);
  delete sys;
}

// A new per-thread record of system s, destroyed with it; the caller uses it from one thread only.
OIIO::TextureSystem::Perthread* new_thread_info(void* s) {
  auto* sys = static_cast<System*>(s);
  OIIO::TextureSystem::Perthread* p = sys->ts->create_thread_info();
  const std::lock_guard lock(sys->mutex);
  sys->thread_infos.push_back(p);
  return p;
}

float max_of(OIIO::TypeDesc t) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8: return 255.0f;
    case OIIO::TypeDesc::INT8: return 127.0f;
    case OIIO::TypeDesc::UINT16: return 65535.0f;
    case OIIO::TypeDesc::INT16: return 32767.0f;
    case OIIO::TypeDesc::UINT32: return 4294967295.0f;
    case OIIO::TypeDesc::INT32: return 2147483647.0f;
    default: return 1.0f;  // half, float, double: stored as is
  }
}

// OpenImageIO may report one problem several times, a line each: Kiln's messages are one line.
std::string first_line(const std::string& e) {
  std::string line = e.substr(0, e.find('\n'));
  while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
  return line;
}

// ---- decoded files ----------------------------------------------------------------------------------------------

// The texture system filters, and builds MIP levels from, what a file's ImageInput hands it. To filter linear values
// of an sRGB- or gamma-encoded 8- or 16-bit file, the cache knows it by a name that carries the decoding, and reads
// it through DecodedInput: the file's own reader (asked to leave alpha unassociated), its values turned to linear
// floats scanline by scanline.
constexpr char kDecodeSeparator = '\x1f';  // cannot occur in a path a scene names

std::string decoded_name(const std::string& path, const TextureDecode& d) {
  std::string how = "linear";
  if (d.kind == TextureDecodeKind::Srgb) how = "srgb";
  if (d.kind == TextureDecodeKind::Gamma) how = std::to_string(d.gamma);
  return path + kDecodeSeparator + how;
}

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

class DecodedInput final : public OIIO::ImageInput {
 public:
  const char* format_name() const override { return "kiln-decoded"; }
  bool open(const std::string& name, OIIO::ImageSpec& newspec) override {
    const size_t sep = name.rfind(kDecodeSeparator);
    if (sep == std::string::npos) return false;
    const std::string how = name.substr(sep + 1);
    srgb_ = how == "srgb";
    gamma_ = srgb_ || how == "linear" ? 1.0f : std::strtof(how.c_str(), nullptr);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    in_ = OIIO::ImageInput::open(name.substr(0, sep), &config);
    if (!in_) {
      errorfmt("{}", OIIO::geterror());
      return false;
    }
    m_spec = in_->spec();
    m_spec.set_format(OIIO::TypeDesc::FLOAT);
    m_spec.tile_width = m_spec.tile_height = m_spec.tile_depth = 0;  // served as scanlines
    m_spec.erase_attribute("oiio:SHA-1");  // not the file's pixels: must not be shared with the undecoded file
    newspec = m_spec;
    return true;
  }
  bool close() override {
    in_.reset();
    return true;
  }
  bool read_native_scanline(int subimage, int miplevel, int y, int z, void* data) override {
    if (subimage != 0 || miplevel != 0 || !in_) return false;
    float* out = static_cast<float*>(data);
    if (!in_->read_scanlines(0, 0, y, y + 1, z, 0, m_spec.nchannels, OIIO::TypeDesc::FLOAT, out)) {
      errorfmt("{}", in_->geterror());
      return false;
    }
    const size_t n = size_t(m_spec.width) * size_t(m_spec.nchannels);
    if (srgb_)
      for (size_t i = 0; i < n; ++i) out[i] = srgb_to_linear(out[i]);
    else if (gamma_ != 1.0f)
      for (size_t i = 0; i < n; ++i) out[i] = std::pow(out[i], gamma_);
    return true;
  }

 private:
  std::unique_ptr<OIIO::ImageInput> in_;
  bool srgb_ = false;
  float gamma_ = 1.0f;
};

OIIO::ImageInput* create_decoded_input() { return new DecodedInput; }

bool integer_format(OIIO::TypeDesc t) { return max_of(t) > 1.0f; }

OIIO::TextureSystem::TextureHandle* texture_handle(System* sys, const std::string& name, OIIO::ImageSpec& spec,
                                                   std::string& error) {
  OIIO::TextureSystem* ts = sys->ts;
  const OIIO::ustring u(name);
  sys->files.push_back(u);
  OIIO::TextureSystem::TextureHandle* h = ts->get_texture_handle(u);
  if (!h || !ts->get_imagespec(h, nullptr, 0, spec) || !ts->good(h)) {
    error = first_line(ts->geterror());
    if (error.empty()) error = "not an image OpenImageIO can read";
    return nullptr;
  }
  return h;
}

void* texture_open(void* s, const std::string& path, const TextureDecode& decode, TextureFileInfo& info,
                   std::string& error) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    error = "no such file";
    return nullptr;
  }
  auto* sys = static_cast<System*>(s);
  OIIO::TextureSystem* ts = sys->ts;
  OIIO::ImageSpec spec;
  OIIO::TextureSystem::TextureHandle* h = texture_handle(sys, path, spec, error);
  if (!h) return nullptr;
  const bool decoded = decode.kind != TextureDecodeKind::Linear && integer_format(spec.format);
  const bool raw_alpha = decode.unassociated_alpha && spec.alpha_channel >= 0;
  if (decoded || raw_alpha) {
    const std::string name = decoded_name(path, decode);
    ts->imagecache()->add_file(OIIO::ustring(name), &create_decoded_input);
    h = texture_handle(sys, name, spec, error);
    if (!h) return nullptr;
  }
  info.width = spec.width;
  info.height = spec.height;
  info.channels = spec.nchannels;
  info.format_max = max_of(spec.format);
  // Reading one texel now finds files whose header is fine but whose pixels are not (truncated data).
  OIIO::TextureOpt opt;
  float probe[3];
  opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
  opt.interpmode = OIIO::TextureOpt::InterpClosest;
  if (!sys->probe) sys->probe = new_thread_info(s);
  if (!ts->texture(h, sys->probe, opt, 0.5f, 0.5f, 0, 0, 0, 0, 3, probe)) {
    error = first_line(ts->geterror());
    if (error.empty()) error = "its pixels cannot be read";
    return nullptr;
  }
  return h;
}

void* texture_thread_info(void* s) { return new_thread_info(s); }

// The OpenImageIO modes of a query: closest / bilinear read the finest level and ignore the derivatives; the
// filtered modes interpolate bilinearly within a level (smart bicubic would cost ~4x the texel reads for a
// difference the footprint's blur mostly hides) and choose levels from the derivatives.
void set_modes(TextureInterp interp, OIIO::TextureOpt& opt) {
  using Opt = OIIO::TextureOpt;
  struct Modes {
    Opt::MipMode mip;
    Opt::InterpMode interp;
  };
  const Modes m = [&]() -> Modes {
    switch (interp) {
      case TextureInterp::Closest: return {Opt::MipModeNoMIP, Opt::InterpClosest};
      case TextureInterp::Bilinear: return {Opt::MipModeNoMIP, Opt::InterpBilinear};
      case TextureInterp::ClosestOneLevel: return {Opt::MipModeOneLevel, Opt::InterpClosest};
      case TextureInterp::BilinearOneLevel: return {Opt::MipModeOneLevel, Opt::InterpBilinear};
      case TextureInterp::Trilinear: return {Opt::MipModeTrilinear, Opt::InterpBilinear};
      case TextureInterp::Anisotropic: return {Opt::MipModeAniso, Opt::InterpBilinear};
    }
    return {Opt::MipModeNoMIP, Opt::InterpClosest};
  }();
  opt.mipmode = m.mip;
  opt.interpmode = m.interp;
}

OIIO::TextureOpt::Wrap wrap_of(TextureWrapMode w) {
  switch (w) {
    case TextureWrapMode::Periodic: return OIIO::TextureOpt::WrapPeriodic;
    case TextureWrapMode::Clamp: return OIIO::TextureOpt::WrapClamp;
    case TextureWrapMode::Black: return OIIO::TextureOpt::WrapBlack;
  }
  return OIIO::TextureOpt::WrapPeriodic;
}

bool texture_lookup(void* s, void* handle, void* thread_info, const TextureQuery& q, float rgba[4]) {
  OIIO::TextureOpt opt;
  set_modes(q.interp, opt);
  opt.swrap = opt.twrap = wrap_of(q.wrap);
  float out[4] = {0, 0, 0, 0};
  // Channels the file lacks come back as 0 (a grey file is spread to RGB by the caller, which knows its channels).
  const bool ok = system_of(s)->texture(static_cast<OIIO::TextureSystem::TextureHandle*>(handle),
                                        static_cast<OIIO::TextureSystem::Perthread*>(thread_info), opt, q.s, q.t,
                                        q.dsdx, q.dtdx, q.dsdy, q.dtdy, 4, out);
  for (int c = 0; c < 4; ++c) rgba[c] = out[c];
  return ok;
}

void texture_stats(void* s, TextureCacheStats& st) {
  OIIO::TextureSystem* ts = system_of(s);
  long long mem = 0, bytes = 0;
  int files = 0;
  ts->getattribute("stat:cache_memory_used", OIIO::TypeDesc::INT64, &mem);
  ts->getattribute("stat:bytes_read", OIIO::TypeDesc::INT64, &bytes);
  ts->getattribute("stat:unique_files", OIIO::TypeDesc::INT, &files);
  st.memory_used = mem;
  st.bytes_read = bytes;
  st.files = files;
}

const ImagePluginApi kApi{kImagePluginAbiVersion, &read_rgb,         &texture_system_create, &texture_system_destroy,
                          &texture_open,          &texture_thread_info, &texture_lookup,       &texture_stats};

}  // namespace
}  // namespace kiln

extern "C" __attribute__((visibility("default"))) const kiln::ImagePluginApi* kiln_image_plugin_v1() {
  return &kiln::kApi;
}
