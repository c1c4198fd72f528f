// Strict text-to-number parsing shared by the scene loaders (XML, JSON, PLY, OBJ). Every number must be a whole
// token, finite and in range: "abc", "1e999", "nan", "inf", "1.5x" are errors, never silently 0. Errors are
// kiln::Error naming the file, the line (when known) and the element, e.g.
//   "scene.xml: line 12 (Camera id=1 / Position): expected 3 numbers, got 2"
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/color.h"
#include "core/vec.h"

namespace kiln {

// Where a piece of text came from, so that parse errors can name it.
struct TextSource {
  std::string file;
  int line = 0;         // 1-based line of the first character of the text; 0 when unknown
  std::string element;  // element path or key, e.g. "Mesh id=3 / Faces"; may be empty

  // Location string for Error: "line 12 (Mesh id=3 / Faces)", "line 12", "Mesh id=3" or "".
  std::string location(int line_override = 0) const;
  [[noreturn]] void fail(const std::string& message, int line_override = 0) const;
};

bool is_space(char c);
std::string_view trim(std::string_view s);
std::vector<std::string_view> split_whitespace(std::string_view s);
// 1-based line of byte `offset` in `text`, counting '\n' (CRLF counts once).
int line_of_offset(std::string_view text, size_t offset);

// Non-throwing single-token conversions: empty result unless the whole token is a finite, in-range value.
// A leading '+' is accepted.
std::optional<double> to_double(std::string_view token);
std::optional<float> to_float(std::string_view token);  // also rejects values that overflow float
std::optional<int64_t> to_int64(std::string_view token);
// "true"/"false" (any case).
std::optional<bool> to_bool(std::string_view token);

// Throwing parsers over a whole text (leading/trailing whitespace allowed).
float parse_float(std::string_view text, const TextSource& src);
int parse_int(std::string_view text, const TextSource& src);
bool parse_bool(std::string_view text, const TextSource& src);
// Any number of values (possibly zero).
std::vector<float> parse_floats(std::string_view text, const TextSource& src);
std::vector<int64_t> parse_ints(std::string_view text, const TextSource& src);
// Exactly out.size() values.
void parse_floats_exact(std::string_view text, std::span<float> out, const TextSource& src);
Vec2f parse_vec2(std::string_view text, const TextSource& src);
Vec3f parse_vec3(std::string_view text, const TextSource& src);
Rgb parse_rgb(std::string_view text, const TextSource& src);

// Whole file as bytes; throws kiln::Error naming the file when it is missing or unreadable. Every loader reads its
// inputs (scene file, PLY / OBJ meshes, binary vertex data) through it.
std::string read_file_bytes(const std::string& path);

// While alive, sees every file read_file_bytes returns on this thread (e.g. to fingerprint a scene by the bytes of
// all the files it was loaded from). Observers nest: the innermost one is called.
class FileReadObserver {
 public:
  using Callback = std::function<void(const std::string& path, std::string_view bytes)>;
  explicit FileReadObserver(Callback callback);
  ~FileReadObserver();
  FileReadObserver(const FileReadObserver&) = delete;
  FileReadObserver& operator=(const FileReadObserver&) = delete;

 private:
  friend std::string read_file_bytes(const std::string& path);
  Callback callback_;
  FileReadObserver* outer_;
};

}  // namespace kiln
