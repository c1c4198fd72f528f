// Kiln's OpenImageIO plugin: a shared module (kiln_oiio_plugin.so, built from renderer/image_io/plugins/) that is
// dlopen()ed the first time Kiln needs OpenImageIO, i.e. for an image that is neither EXR nor PNG.
//
// Why a plugin: Debian's OpenImageIO pulls in ~260 shared libraries (OpenCV, GDAL, FFmpeg, Poppler, OpenVDB, ...)
// whose loading and relocation cost ~0.5 s per process. Linked into `kiln`, every `kiln --version`, `kiln info`
// and error message would pay it. Code that needs OpenImageIO (other image formats; a TextureSystem) belongs in the
// plugin and is reached through this table; nothing outside renderer/image_io/plugins/ links OpenImageIO (a test checks
// that `kiln` starts without it).
//
// Where it is looked for, first hit wins: $KILN_PLUGIN_DIR; the running executable's folder; the install layout
// relative to it (<prefix>/bin/kiln -> <prefix>/<libdir>/kiln/); the build tree it was built in.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace kiln {

inline constexpr int kImagePluginAbiVersion = 4;
inline constexpr const char* kImagePluginEntryPoint = "kiln_image_plugin_v1";

// Texture lookups through OpenImageIO's TextureSystem (mip-mapped, tiled, cached; thread-safe). The handles are
// opaque OpenImageIO objects: a TextureSystem, a TextureHandle per file and a Perthread per thread.
struct TextureSystemOptions {
  float max_memory_mb = 128.0f;  // the tile cache's bound ("max_memory_MB")
  int autotile = 64;             // untiled files (JPEG, PNG) are cached in tiles of this size, not whole
};
struct TextureFileInfo {
  int width = 0, height = 0, channels = 0;
  float format_max = 1.0f;  // the largest value of the file's pixel type (255 for 8 bit; 1 for float), which
                            // OpenImageIO maps to 1
};
// How an 8- or 16-bit file's values become the linear values the texture system filters: as they are (divided by
// the format's maximum), through the sRGB curve, or v^gamma. Decoding happens before filtering and before the MIP
// levels are built (pbrt-v4 decodes when it loads an image). Float files are always read as they are.
// unassociated_alpha: a file with alpha keeps its colour channels as stored (OpenImageIO otherwise multiplies
// them by alpha, as it does for PNG, TGA and TIFF files with unassociated alpha).
enum class TextureDecodeKind { Linear, Srgb, Gamma };
struct TextureDecode {
  TextureDecodeKind kind = TextureDecodeKind::Linear;
  float gamma = 2.2f;
  bool unassociated_alpha = false;
};
// Closest / Bilinear: the finest level only, derivatives unread. ClosestOneLevel / BilinearOneLevel: the same within
// the one MIP level the footprint selects. Trilinear: bilinear in the two MIP levels around the footprint's larger
// axis. Anisotropic: OpenImageIO's anisotropic MIP filter (several bilinear probes along the footprint's major axis,
// at the level of its minor axis): EWA-like.
enum class TextureInterp { Closest, Bilinear, ClosestOneLevel, BilinearOneLevel, Trilinear, Anisotropic };
enum class TextureWrapMode { Periodic, Clamp, Black };
// One lookup at (s, t): s to the right, t down the image (t = 0 is the top row), both in [0, 1] over the image.
struct TextureQuery {
  float s = 0, t = 0;
  // The footprint: change of (s, t) per pixel step along the film's x and y (Trilinear / Anisotropic only).
  float dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;
  TextureInterp interp = TextureInterp::Bilinear;
  TextureWrapMode wrap = TextureWrapMode::Periodic;
};
struct TextureCacheStats {
  int64_t memory_used = 0;  // bytes of tiles held now
  int64_t bytes_read = 0;   // from files, in total
  int files = 0;
};

// Function table returned by the plugin's entry point (extern "C" const ImagePluginApi* kiln_image_plugin_v1()).
// Plugin and Kiln are built together by the same compiler, so C++ standard types may cross the boundary.
struct ImagePluginApi {
  int abi_version = kImagePluginAbiVersion;
  // The first subimage of any format OpenImageIO reads, as interleaved float RGB (grey images replicated).
  // Returns false and fills error when it cannot.
  bool (*read_rgb)(const std::string& path, std::vector<float>& rgb, int& width, int& height,
                   std::string& error) = nullptr;
  // A world's texture system (released by texture_system_destroy); null on failure.
  void* (*texture_system_create)(const TextureSystemOptions& options, std::string& error) = nullptr;
  void (*texture_system_destroy)(void* system) = nullptr;
  // Opens (and checks) one file, decoded as `decode` says; returns its handle, or null with error filled when it is
  // missing or unreadable. The same file opened with two decodings is two textures.
  void* (*texture_open)(void* system, const std::string& path, const TextureDecode& decode, TextureFileInfo& info,
                        std::string& error) = nullptr;
  // A new Perthread record for the calling thread, owned by the system (destroyed with it): ask once per thread.
  void* (*texture_thread_info)(void* system) = nullptr;
  // The first four channels at the query (channels the file lacks are 0; the caller spreads a grey file, knowing
  // its channel count); false when the lookup failed (the result is then black).
  bool (*texture_lookup)(void* system, void* handle, void* thread_info, const TextureQuery& query,
                         float rgba[4]) = nullptr;
  void (*texture_stats)(void* system, TextureCacheStats& stats) = nullptr;
};

// Loads the plugin on first use (thread-safe) and returns its table. Throws kiln::Error naming `needed_for` (a
// file) and the folders searched when the plugin cannot be found or loaded.
const ImagePluginApi& image_plugin(const std::string& needed_for);

}  // namespace kiln
