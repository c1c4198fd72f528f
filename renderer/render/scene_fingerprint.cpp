#include "renderer/render/scene_fingerprint.h"

// Header-only xxHash (Debian's libxxhash-dev): nothing to link, so the renderer stays free of OpenImageIO.
#define XXH_INLINE_ALL
#include <xxhash.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unordered_set>

#include "core/error.h"
#include "scenes/parse_util.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

constexpr size_t kHashDigits = 16;
constexpr uint64_t kMissingHash = ~uint64_t(0);
// External files (textures, environment maps, volume grids) can be large: they are hashed in pieces, never held.
constexpr size_t kHashChunkBytes = size_t(1) << 20;

std::string hex64(uint64_t h) {
  char hex[kHashDigits + 1];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

fs::path absolute_normal(const std::string& path) {
  std::error_code ec;
  const fs::path a = fs::absolute(path, ec);
  return (ec ? fs::path(path) : a).lexically_normal();
}

// The files in order, each once, with their XXH64; names relative to the scene file's folder.
class FileList {
 public:
  explicit FileList(const std::string& scene_path) : base_(absolute_normal(scene_path).parent_path()) {}

  bool add_first(const std::string& path) { return seen_.insert(absolute_normal(path).string()).second; }

  void add(const std::string& path, uint64_t hash, uint64_t bytes) {
    const fs::path abs = absolute_normal(path);
    const fs::path rel = abs.lexically_relative(base_);
    hashes_.push_back(hash);
    files_.push_back({rel.empty() ? abs.generic_string() : rel.generic_string(), hex64(hash), bytes});
  }

  SceneFingerprint finish() const {
    SceneFingerprint f;
    // Byte order fixed (little-endian), so the identity is the same on every machine.
    std::string packed;
    for (uint64_t h : hashes_)
      for (int i = 0; i < 8; ++i) packed.push_back(char((h >> (8 * i)) & 0xffu));
    f.hash = hex64(XXH64(packed.data(), packed.size(), 0));
    f.files = files_;
    for (const FingerprintedFile& file : files_) f.bytes += file.bytes;
    return f;
  }

 private:
  fs::path base_;
  std::unordered_set<std::string> seen_;
  std::vector<uint64_t> hashes_;
  std::vector<FingerprintedFile> files_;
};

// A file that cannot be opened is listed as missing (kMissingHash): the world build that follows reports it,
// naming the element that uses it, and no part of such a scene is ever written.
void hash_external_file(const std::string& path, const std::string& scene_path, FileList& list) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    list.add(path, kMissingHash, 0);
    return;
  }
  XXH64_state_t state;
  XXH64_reset(&state, 0);
  std::string chunk(kHashChunkBytes, '\0');
  uint64_t bytes = 0;
  while (in) {
    in.read(chunk.data(), std::streamsize(chunk.size()));
    const size_t got = size_t(in.gcount());
    XXH64_update(&state, chunk.data(), got);
    bytes += got;
  }
  if (in.bad()) throw Error(path, "", "cannot read a file the scene " + scene_path + " uses");
  list.add(path, XXH64_digest(&state), bytes);
}

}  // namespace

SceneDesc load_scene_fingerprinted(const std::string& path, const LoadOptions& options, SceneFingerprint& fingerprint) {
  FileList list(path);
  const FileReadObserver observer([&](const std::string& file, std::string_view data) {
    if (list.add_first(file)) list.add(file, XXH64(data.data(), data.size(), 0), data.size());
  });
  SceneDesc scene = load_scene(path, options);
  for (const std::string& file : scene.external_files)
    if (list.add_first(file)) hash_external_file(file, path, list);
  fingerprint = list.finish();
  return scene;
}

std::string scene_files_metadata(const SceneFingerprint& fingerprint) {
  std::string s;
  for (const FingerprintedFile& f : fingerprint.files) {
    if (!s.empty()) s.push_back('\n');
    s.append(f.hash).append(" ").append(f.name);
  }
  return s;
}

std::vector<FingerprintedFile> parse_scene_files_metadata(const std::string& text) {
  std::vector<FingerprintedFile> out;
  size_t at = 0;
  while (at < text.size()) {
    const size_t eol = std::min(text.find('\n', at), text.size());
    const std::string line = text.substr(at, eol - at);
    at = eol + 1;
    if (line.size() < kHashDigits + 2 || line[kHashDigits] != ' ' ||
        line.find_first_not_of("0123456789abcdef") < kHashDigits)
      return {};
    out.push_back({line.substr(kHashDigits + 1), line.substr(0, kHashDigits), 0});
  }
  return out;
}

std::optional<std::string> first_file_difference(const std::vector<FingerprintedFile>& a,
                                                 const std::vector<FingerprintedFile>& b) {
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (a[i].name != b[i].name) return "file #" + std::to_string(i + 1) + ": " + a[i].name + " vs " + b[i].name;
    if (a[i].hash != b[i].hash) return a[i].name + " (hash " + a[i].hash + " vs " + b[i].hash + ")";
  }
  if (a.size() > b.size()) return a[b.size()].name + " (only in the first)";
  if (b.size() > a.size()) return b[a.size()].name + " (only in the second)";
  return std::nullopt;
}

}  // namespace kiln
