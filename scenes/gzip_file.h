// Whole-file reads that see through gzip compression (pbrt scenes ship ".ply.gz" meshes and ".pbrt.gz" includes).
#pragma once
#include <string>
#include <string_view>

namespace kiln {

// A decompressed file bigger than this is refused (a corrupt or hostile header cannot exhaust memory).
inline constexpr size_t kMaxDecompressedBytes = size_t(4) << 30;

// The file's bytes, gunzipped when its name ends in ".gz". Throws kiln::Error naming the file when it is missing,
// unreadable, not valid gzip, truncated, or decompresses to more than kMaxDecompressedBytes.
std::string read_file_maybe_gzip(const std::string& path);
// `data` as a gzip stream (for writing .gz test fixtures).
std::string gzip(std::string_view data);
// Gunzips `data` (one or more concatenated gzip members); `file` names it in errors.
std::string gunzip(std::string_view data, const std::string& file, size_t max_bytes = kMaxDecompressedBytes);

}  // namespace kiln
