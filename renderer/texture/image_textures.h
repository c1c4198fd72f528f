// The image textures of one world: OpenImageIO's TextureSystem through the plugin (renderer/image_io/image_plugin.h),
// created when the first image is opened (a world whose textures are all procedural never loads OpenImageIO) and
// released with the world. Lookups are thread-safe; each thread keeps its own OpenImageIO record per world.
#pragma once
#include <cstdint>
#include <string>

#include "renderer/image_io/image_plugin.h"

namespace kiln {

struct OpenedImage {
  void* handle = nullptr;
  TextureFileInfo info;
};

class TextureImages {
 public:
  explicit TextureImages(const TextureSystemOptions& options);
  ~TextureImages();
  TextureImages(const TextureImages&) = delete;
  TextureImages& operator=(const TextureImages&) = delete;

  // Opens `path` decoded as `decode`. Throws kiln::Error naming `file` (the scene) and `who` (the element or line
  // that names the image) when it is missing or unreadable, or when OpenImageIO cannot be loaded.
  OpenedImage open(const std::string& path, const TextureDecode& decode, const std::string& file,
                   const std::string& who);
  // The first four channels at q (missing channels 0); black when the lookup fails.
  void lookup(void* handle, const TextureQuery& q, float rgba[4]) const;

  bool built() const { return system_ != nullptr; }
  size_t images() const { return images_; }
  float cache_limit_mb() const { return options_.max_memory_mb; }
  TextureCacheStats cache_stats() const;

 private:
  TextureSystemOptions options_;
  const ImagePluginApi* api_ = nullptr;
  void* system_ = nullptr;
  size_t images_ = 0;
  uint64_t generation_ = 0;  // tells a thread's cached record of this world from one of an earlier world's
};

}  // namespace kiln
