// Kiln's OpenImageIO plugin (renderer/image_io/image_plugin.h explains why it is a separately loaded module). Built as
// kiln_oiio_plugin.so; the only Kiln code that links OpenImageIO.
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <filesystem>
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

void* texture_open(void* s, const std::string& path, TextureFileInfo& info, std::string& error) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    error = "no such file";
    return nullptr;
  }
  auto* sys = static_cast<System*>(s);
  OIIO::TextureSystem* ts = sys->ts;
  const OIIO::ustring name(path);
  sys->files.push_back(name);
  OIIO::TextureSystem::TextureHandle* h = ts->get_texture_handle(name);
  OIIO::ImageSpec spec;
  if (!h || !ts->get_imagespec(h, nullptr, 0, spec) || !ts->good(h)) {
    error = first_line(ts->geterror());
    if (error.empty()) error = "not an image OpenImageIO can read";
    return nullptr;
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
      case TextureInterp::Trilinear: return {Opt::MipModeTrilinear, Opt::InterpBilinear};
      case TextureInterp::Anisotropic: return {Opt::MipModeAniso, Opt::InterpBilinear};
    }
    return {Opt::MipModeNoMIP, Opt::InterpClosest};
  }();
  opt.mipmode = m.mip;
  opt.interpmode = m.interp;
}

bool texture_lookup(void* s, void* handle, void* thread_info, const TextureQuery& q, float rgb[3]) {
  OIIO::TextureOpt opt;
  set_modes(q.interp, opt);
  opt.swrap = opt.twrap =
      q.wrap == TextureWrapMode::Clamp ? OIIO::TextureOpt::WrapClamp : OIIO::TextureOpt::WrapPeriodic;
  float out[3] = {0, 0, 0};
  // Channels the file lacks come back as 0 (a grey file is spread to RGB by the caller, which knows its channels).
  const bool ok = system_of(s)->texture(static_cast<OIIO::TextureSystem::TextureHandle*>(handle),
                                        static_cast<OIIO::TextureSystem::Perthread*>(thread_info), opt, q.s, q.t,
                                        q.dsdx, q.dtdx, q.dsdy, q.dtdy, 3, out);
  rgb[0] = out[0];
  rgb[1] = out[1];
  rgb[2] = out[2];
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
