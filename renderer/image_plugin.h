// Kiln's OpenImageIO plugin: a shared module (kiln_oiio_plugin.so, built from renderer/plugins/) that is
// dlopen()ed the first time Kiln needs OpenImageIO, i.e. for an image that is neither EXR nor PNG.
//
// Why a plugin: Debian's OpenImageIO pulls in ~260 shared libraries (OpenCV, GDAL, FFmpeg, Poppler, OpenVDB, ...)
// whose loading and relocation cost ~0.5 s per process. Linked into `kiln`, every `kiln --version`, `kiln info`
// and error message would pay it. Code that needs OpenImageIO (other image formats; a TextureSystem) belongs in the
// plugin and is reached through this table; nothing outside renderer/plugins/ links OpenImageIO (a test checks
// that `kiln` starts without it).
//
// Where it is looked for, first hit wins: $KILN_PLUGIN_DIR; the running executable's folder; the install layout
// relative to it (<prefix>/bin/kiln -> <prefix>/<libdir>/kiln/); the build tree it was built in.
#pragma once
#include <string>
#include <vector>

namespace kiln {

inline constexpr int kImagePluginAbiVersion = 1;
inline constexpr const char* kImagePluginEntryPoint = "kiln_image_plugin_v1";

// Function table returned by the plugin's entry point (extern "C" const ImagePluginApi* kiln_image_plugin_v1()).
// Plugin and Kiln are built together by the same compiler, so C++ standard types may cross the boundary.
struct ImagePluginApi {
  int abi_version = kImagePluginAbiVersion;
  // The first subimage of any format OpenImageIO reads, as interleaved float RGB (grey images replicated).
  // Returns false and fills error when it cannot.
  bool (*read_rgb)(const std::string& path, std::vector<float>& rgb, int& width, int& height,
                   std::string& error) = nullptr;
};

// Loads the plugin on first use (thread-safe) and returns its table. Throws kiln::Error naming `needed_for` (a
// file) and the folders searched when the plugin cannot be found or loaded.
const ImagePluginApi& image_plugin(const std::string& needed_for);

}  // namespace kiln
