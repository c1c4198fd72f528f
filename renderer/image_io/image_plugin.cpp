#include "renderer/image_io/image_plugin.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

#include "core/error.h"

// Set by CMake: the folder the plugin is built into, and the plugin folder relative to an installed `kiln`.
#ifndef KILN_PLUGIN_BUILD_DIR
#define KILN_PLUGIN_BUILD_DIR ""
#endif
#ifndef KILN_PLUGIN_INSTALL_SUBDIR
#define KILN_PLUGIN_INSTALL_SUBDIR "../lib/kiln"
#endif

namespace kiln {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPluginFile = "kiln_oiio_plugin.so";

std::vector<fs::path> search_dirs() {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("KILN_PLUGIN_DIR"); env && *env) dirs.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    dirs.push_back(exe.parent_path());
    dirs.push_back((exe.parent_path() / KILN_PLUGIN_INSTALL_SUBDIR).lexically_normal());
  }
  if (*KILN_PLUGIN_BUILD_DIR) dirs.emplace_back(KILN_PLUGIN_BUILD_DIR);
  return dirs;
}

struct LoadResult {
  const ImagePluginApi* api = nullptr;
  std::string error;
};

LoadResult load_plugin() {
  std::string searched;
  for (const fs::path& dir : search_dirs()) {
    const fs::path file = dir / kPluginFile;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
      searched += (searched.empty() ? "" : ", ") + dir.string();
      continue;
    }
    // Never closed: the plugin's code stays in use until the process ends.
    void* handle = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) return {nullptr, "cannot load " + file.string() + ": " + ::dlerror()};
    using Entry = const ImagePluginApi* (*)();
    const auto entry = reinterpret_cast<Entry>(::dlsym(handle, kImagePluginEntryPoint));
    const ImagePluginApi* api = entry ? entry() : nullptr;
    if (!api || api->abi_version != kImagePluginAbiVersion || !api->read_rgb || !api->texture_lookup)
      return {nullptr, file.string() + " is not a plugin of this Kiln version (rebuild it)"};
    return {api, {}};
  }
  return {nullptr, std::string(kPluginFile) + " not found (searched " + searched + "; set KILN_PLUGIN_DIR)"};
}

}  // namespace

const ImagePluginApi& image_plugin(const std::string& needed_for) {
  static const LoadResult loaded = load_plugin();  // once per process, thread-safe
  if (!loaded.api) throw Error(needed_for, "", "this image format needs Kiln's OpenImageIO plugin: " + loaded.error);
  return *loaded.api;
}

}  // namespace kiln
