#include "scenes/gzip_file.h"

#include <zlib.h>

#include <algorithm>
#include <climits>

#include "core/error.h"
#include "scenes/parse_util.h"

namespace kiln {
namespace {

// zlib's window bits for "gzip wrapper only" (15-bit window + 16).
constexpr int kGzipWindowBits = 15 + 16;
constexpr size_t kChunk = size_t(1) << 20;

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

}  // namespace

std::string gunzip(std::string_view data, const std::string& file, size_t max_bytes) {
  std::string out;
  z_stream zs{};
  if (inflateInit2(&zs, kGzipWindowBits) != Z_OK) throw Error(file, "", "cannot initialise zlib");
  size_t consumed = 0;
  int rc = Z_OK;
  while (true) {
    if (zs.avail_in == 0 && consumed < data.size()) {
      const size_t n = std::min(data.size() - consumed, size_t(UINT_MAX));
      zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data() + consumed));
      zs.avail_in = uInt(n);
      consumed += n;
    }
    const size_t old = out.size();
    if (old >= max_bytes) {
      inflateEnd(&zs);
      throw Error(file, "", "decompresses to more than " + std::to_string(max_bytes >> 20) + " MiB; refused");
    }
    const size_t grow = std::min(kChunk, max_bytes - old);
    out.resize(old + grow);
    zs.next_out = reinterpret_cast<Bytef*>(out.data() + old);
    zs.avail_out = uInt(grow);
    rc = inflate(&zs, Z_NO_FLUSH);
    out.resize(old + (grow - zs.avail_out));
    if (rc == Z_STREAM_END) {
      // Concatenated members (gzip allows them): continue when input remains.
      if (zs.avail_in == 0 && consumed >= data.size()) break;
      if (inflateReset(&zs) != Z_OK) break;
      continue;
    }
    if (rc == Z_BUF_ERROR && zs.avail_in == 0 && consumed >= data.size()) {
      inflateEnd(&zs);
      throw Error(file, "", "truncated gzip data");
    }
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      const std::string why = zs.msg ? zs.msg : "error " + std::to_string(rc);
      inflateEnd(&zs);
      throw Error(file, "", "invalid gzip data (" + why + ")");
    }
  }
  inflateEnd(&zs);
  return out;
}

std::string gzip(std::string_view data) {
  z_stream zs{};
  if (deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, kGzipWindowBits, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw Error("cannot initialise zlib");
  std::string out(deflateBound(&zs, uLong(data.size())) + 64, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = uInt(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = uInt(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw Error("gzip compression failed");
  return out;
}

std::string read_file_maybe_gzip(const std::string& path) {
  std::string bytes = read_file_bytes(path);
  if (!ends_with(path, ".gz")) return bytes;
  return gunzip(bytes, path);
}

}  // namespace kiln
