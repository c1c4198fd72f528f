#include "scenes/pbrt/tokenizer.h"

#include "core/error.h"

namespace kiln {
namespace {

constexpr size_t kMaxDescribedToken = 40;

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
bool ends_word(char c) { return is_blank(c) || c == '"' || c == '[' || c == ']'; }

std::string location(int line) { return "line " + std::to_string(line); }

}  // namespace

PbrtTokenizer::PbrtTokenizer(std::string text, std::string file) : text_(std::move(text)), file_(std::move(file)) {
  // UTF-16 text would tokenize as garbage words; say what it is instead.
  if (text_.size() >= 2 && ((uint8_t(text_[0]) == 0xFE && uint8_t(text_[1]) == 0xFF) ||
                            (uint8_t(text_[0]) == 0xFF && uint8_t(text_[1]) == 0xFE)))
    throw Error(file_, location(1), "the file is UTF-16 encoded; pbrt scene files are ASCII / UTF-8");
}

std::optional<PbrtToken> PbrtTokenizer::next() {
  const size_t n = text_.size();
  while (pos_ < n) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (is_blank(c)) {
      ++pos_;
    } else if (c == '#') {
      while (pos_ < n && text_[pos_] != '\n' && text_[pos_] != '\r') ++pos_;
    } else if (c == '[' || c == ']') {
      ++pos_;
      return PbrtToken{c == '[' ? PbrtTokenKind::OpenBracket : PbrtTokenKind::CloseBracket,
                       std::string_view(text_).substr(pos_ - 1, 1), line_};
    } else if (c == '"') {
      const size_t start = ++pos_;
      while (true) {
        if (pos_ >= n) throw Error(file_, location(line_), "unterminated string: the file ends inside it");
        const char s = text_[pos_];
        if (s == '"') break;
        const bool escape = s == '\\' && pos_ + 1 < n;
        const char c2 = escape ? text_[pos_ + 1] : s;
        if (c2 == '\n' || c2 == '\r')
          throw Error(file_, location(line_), "unterminated string: a newline inside quotes");
        pos_ += escape ? 2 : 1;
      }
      const std::string_view body = std::string_view(text_).substr(start, pos_ - start);
      ++pos_;  // closing quote
      return PbrtToken{PbrtTokenKind::String, body, line_};
    } else {
      const size_t start = pos_;
      while (pos_ < n && !ends_word(text_[pos_])) ++pos_;
      return PbrtToken{PbrtTokenKind::Word, std::string_view(text_).substr(start, pos_ - start), line_};
    }
  }
  return std::nullopt;
}

std::string pbrt_unescape(const PbrtToken& t, const std::string& file) {
  std::string out;
  out.reserve(t.text.size());
  for (size_t i = 0; i < t.text.size(); ++i) {
    char c = t.text[i];
    if (c == '\\') {
      if (++i >= t.text.size()) throw Error(file, location(t.line), "a string ends with a lone backslash");
      switch (t.text[i]) {
        case 'b': c = '\b'; break;
        case 'f': c = '\f'; break;
        case 'n': c = '\n'; break;
        case 'r': c = '\r'; break;
        case 't': c = '\t'; break;
        case '\\': c = '\\'; break;
        case '\'': c = '\''; break;
        case '"': c = '"'; break;
        default: throw Error(file, location(t.line), std::string("unknown escape '\\") + t.text[i] + "' in a string");
      }
    }
    out.push_back(c);
  }
  return out;
}

std::string pbrt_describe(const PbrtToken& t) {
  std::string s(t.text.substr(0, kMaxDescribedToken));
  if (t.text.size() > kMaxDescribedToken) s += "...";
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) c = '?';
  return t.kind == PbrtTokenKind::String ? "\"" + s + "\"" : "'" + s + "'";
}

}  // namespace kiln
