// A scene's identity for split renders: the hashes of every file the render reads, in a defined order. First the
// files the loader read through read_file_bytes (scenes/parse_util.h: the scene file, its includes, PLY / OBJ /
// binary data, spectrum files), in read order; then SceneDesc::external_files (texture images, environment maps,
// normal and bump maps, volume grids), in the order the loader listed them. A file read twice counts once, at its
// first place. Paths are not hashed, so machines that mount the scene at different places agree; a changed byte in
// any of these files gives another identity.
//
// `kiln render` writes the identity into every part's EXR (kiln:scene_hash, and kiln:scene_files with one line per
// file, "<16 hex digits> <name>", the name relative to the scene file's folder), `kiln merge` refuses parts whose
// identities differ and names the first file that differs, and `kiln info` lists the files.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scenes/loader.h"

namespace kiln {

struct FingerprintedFile {
  std::string name;  // relative to the scene file's folder ("earth.jpg", "../meshes/a.ply"); absolute when unrelated
  std::string hash;  // 16 hex digits: XXH64 of the file's bytes
  uint64_t bytes = 0;
};

struct SceneFingerprint {
  std::string hash;  // 16 hex digits: XXH64 over the files' hashes, in order
  std::vector<FingerprintedFile> files;
  uint64_t bytes = 0;  // all files together
};

// load_scene that also fingerprints every file the render of the scene reads. Throws kiln::Error naming an
// external file that cannot be read.
SceneDesc load_scene_fingerprinted(const std::string& path, const LoadOptions& options, SceneFingerprint& fingerprint);

// The kiln:scene_files value: "<hash> <name>" per file, '\n'-separated, in the fingerprint's order.
std::string scene_files_metadata(const SceneFingerprint& fingerprint);
// Its inverse; empty for text in another form (a part written by an older kiln).
std::vector<FingerprintedFile> parse_scene_files_metadata(const std::string& text);

// Where two parts' file lists first disagree, e.g. "earth.jpg (hash 0123... vs 4567...)"; empty when they agree.
std::optional<std::string> first_file_difference(const std::vector<FingerprintedFile>& a,
                                                 const std::vector<FingerprintedFile>& b);

}  // namespace kiln
