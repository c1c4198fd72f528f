// Tokenizer for the pbrt-v4 scene language (pbrt.org/fileformat-v4): whitespace-separated words, "quoted strings"
// (escapes \b \f \n \r \t \\ \' \"; a string may not span lines), the brackets [ and ], and # comments to the end
// of the line. A word runs until whitespace, a quote or a bracket, so `[0 1]` and `"a""b"` split as pbrt splits
// them. Every token knows its 1-based line for error messages.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace kiln {

enum class PbrtTokenKind : uint8_t { Word, String, OpenBracket, CloseBracket };

struct PbrtToken {
  PbrtTokenKind kind = PbrtTokenKind::Word;
  std::string_view text;  // Word: as written; String: between the quotes, escapes not yet decoded
  int line = 0;
  bool is_word(std::string_view w) const { return kind == PbrtTokenKind::Word && text == w; }
};

class PbrtTokenizer {
 public:
  // `file` names the text in error messages; the tokenizer owns the text.
  PbrtTokenizer(std::string text, std::string file);

  // Next token, or nothing at the end of the text. Throws kiln::Error (file and line) on an unterminated string.
  std::optional<PbrtToken> next();
  const std::string& file() const { return file_; }
  // Line of the most recently returned token (or of the end of the text).
  int line() const { return line_; }

 private:
  std::string text_, file_;
  size_t pos_ = 0;
  int line_ = 1;
};

// One file's tokens with one token of lookahead. A parameter list that an included file ends may go on in the
// including file's cursor (pbrt reads one token stream across files; the parser continues it there).
class PbrtCursor {
 public:
  explicit PbrtCursor(PbrtTokenizer t) : tok_(std::move(t)) {}
  std::optional<PbrtToken> peek() {
    if (!ahead_) ahead_ = tok_.next();
    return ahead_;
  }
  std::optional<PbrtToken> next() {
    if (ahead_) return std::exchange(ahead_, std::nullopt);
    return tok_.next();
  }
  const std::string& file() const { return tok_.file(); }
  int line() const { return ahead_ ? ahead_->line : tok_.line(); }

 private:
  PbrtTokenizer tok_;
  std::optional<PbrtToken> ahead_;
};

// The contents of a String token with its escapes decoded; throws kiln::Error on an unknown escape.
std::string pbrt_unescape(const PbrtToken& t, const std::string& file);

// Short printable form of a token for messages ("[", "\"abc\"", "Shape"), cut after a few dozen characters.
std::string pbrt_describe(const PbrtToken& t);

}  // namespace kiln
