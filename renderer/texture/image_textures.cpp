#include "renderer/texture/image_textures.h"

#include <atomic>

#include "core/error.h"

namespace kiln {
namespace {

std::atomic<uint64_t> g_next_generation{1};

// The calling thread's OpenImageIO Perthread record of the system it last used.
struct ThreadTextureInfo {
  uint64_t generation = 0;
  void* info = nullptr;
};
thread_local ThreadTextureInfo t_info;

}  // namespace

TextureImages::TextureImages(const TextureSystemOptions& options)
    : options_(options), generation_(g_next_generation.fetch_add(1)) {}

TextureImages::~TextureImages() {
  if (system_) api_->texture_system_destroy(system_);
}

OpenedImage TextureImages::open(const std::string& path, const TextureDecode& decode, const std::string& file,
                                const std::string& who) {
  if (!system_) {
    api_ = &image_plugin(file);
    std::string error;
    system_ = api_->texture_system_create(options_, error);
    if (!system_) throw Error(file, who, error);
  }
  OpenedImage image;
  std::string error;
  image.handle = api_->texture_open(system_, path, decode, image.info, error);
  if (!image.handle) throw Error(file, who, "image '" + path + "': " + error);
  ++images_;
  return image;
}

void TextureImages::lookup(void* handle, const TextureQuery& q, float rgba[4]) const {
  if (t_info.generation != generation_) t_info = {generation_, api_->texture_thread_info(system_)};
  api_->texture_lookup(system_, handle, t_info.info, q, rgba);
}

TextureCacheStats TextureImages::cache_stats() const {
  TextureCacheStats s;
  if (system_) api_->texture_stats(system_, s);
  return s;
}

}  // namespace kiln
