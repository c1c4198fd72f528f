#include "scenes/parse_util.h"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <utility>

#include "core/error.h"

namespace kiln {
namespace {

constexpr size_t kMaxQuotedToken = 40;  // long garbage tokens are cut in messages

std::string quote(std::string_view token) {
  std::string s(token.substr(0, kMaxQuotedToken));
  if (token.size() > kMaxQuotedToken) s += "...";
  return "'" + s + "'";
}

// Why a token is not a finite number (for messages); empty when it is one.
std::string number_problem(std::string_view token) {
  if (token.empty()) return "expected a number, got nothing";
  std::string_view t = token;
  if (t.front() == '+') t.remove_prefix(1);
  double v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec == std::errc::result_out_of_range) return quote(token) + " is out of range";
  if (ec != std::errc() || ptr != t.data() + t.size()) return "expected a number, got " + quote(token);
  if (!std::isfinite(v)) return quote(token) + " is not a finite number";
  if (std::abs(v) > double(std::numeric_limits<float>::max())) return quote(token) + " is out of range";
  return {};
}

// Whitespace tokenizer that knows the line of each token relative to the start of the text.
class Tokens {
 public:
  explicit Tokens(std::string_view s) : s_(s) {}
  // Next token or empty view at the end.
  std::string_view next() {
    while (pos_ < s_.size() && is_space(s_[pos_])) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
    const size_t start = pos_;
    while (pos_ < s_.size() && !is_space(s_[pos_])) ++pos_;
    return s_.substr(start, pos_ - start);
  }
  int line_delta() const { return line_; }

 private:
  std::string_view s_;
  size_t pos_ = 0;
  int line_ = 0;
};

int token_line(const TextSource& src, const Tokens& tok) { return src.line > 0 ? src.line + tok.line_delta() : 0; }

float float_or_fail(std::string_view token, const TextSource& src, const Tokens& tok) {
  if (auto v = to_float(token)) return *v;
  src.fail(number_problem(token), token_line(src, tok));
}

int64_t int_or_fail(std::string_view token, const TextSource& src, const Tokens& tok) {
  if (auto v = to_int64(token)) return *v;
  // Overflow (of int64 or of any number) gets its own message; everything else is "not an integer".
  std::string_view t = token;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  const bool overflow = (ec == std::errc::result_out_of_range && ptr == t.data() + t.size()) ||
                        number_problem(token).find("out of range") != std::string::npos;
  src.fail(overflow ? quote(token) + " is out of range" : "expected an integer, got " + quote(token),
           token_line(src, tok));
}

}  // namespace

std::string TextSource::location(int line_override) const {
  const int l = line_override > 0 ? line_override : line;
  std::string s;
  if (l > 0) s = "line " + std::to_string(l);
  if (!element.empty()) s += s.empty() ? element : " (" + element + ")";
  return s;
}

void TextSource::fail(const std::string& message, int line_override) const {
  throw Error(file, location(line_override), message);
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_whitespace(std::string_view s) {
  std::vector<std::string_view> out;
  Tokens tok(s);
  for (auto t = tok.next(); !t.empty(); t = tok.next()) out.push_back(t);
  return out;
}

int line_of_offset(std::string_view text, size_t offset) {
  offset = std::min(offset, text.size());
  int line = 1;
  for (size_t i = 0; i < offset; ++i)
    if (text[i] == '\n') ++line;
  return line;
}

std::optional<double> to_double(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double v = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<float> to_float(std::string_view token) {
  const auto d = to_double(token);
  if (!d || std::abs(*d) > double(std::numeric_limits<float>::max())) return std::nullopt;
  return float(*d);
}

std::optional<int64_t> to_int64(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return v;
}

std::optional<bool> to_bool(std::string_view token) {
  auto eq = [&](std::string_view w) {
    if (token.size() != w.size()) return false;
    for (size_t i = 0; i < w.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(token[i])) != w[i]) return false;
    return true;
  };
  if (eq("true")) return true;
  if (eq("false")) return false;
  return std::nullopt;
}

float parse_float(std::string_view text, const TextSource& src) {
  float v = 0;
  parse_floats_exact(text, std::span<float>(&v, 1), src);
  return v;
}

int parse_int(std::string_view text, const TextSource& src) {
  Tokens tok(text);
  const auto t = tok.next();
  if (t.empty()) src.fail("expected an integer, got nothing");
  const int64_t v = int_or_fail(t, src, tok);
  if (!tok.next().empty()) src.fail("expected one integer, got " + quote(trim(text)));
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    src.fail(quote(t) + " is out of range");
  return int(v);
}

bool parse_bool(std::string_view text, const TextSource& src) {
  if (auto b = to_bool(trim(text))) return *b;
  src.fail("expected true or false, got " + quote(trim(text)));
}

std::vector<float> parse_floats(std::string_view text, const TextSource& src) {
  std::vector<float> out;
  out.reserve(text.size() / 4);  // a number plus separator is rarely shorter than 4 bytes
  Tokens tok(text);
  for (auto t = tok.next(); !t.empty(); t = tok.next()) out.push_back(float_or_fail(t, src, tok));
  return out;
}

std::vector<int64_t> parse_ints(std::string_view text, const TextSource& src) {
  std::vector<int64_t> out;
  out.reserve(text.size() / 3);
  Tokens tok(text);
  for (auto t = tok.next(); !t.empty(); t = tok.next()) out.push_back(int_or_fail(t, src, tok));
  return out;
}

void parse_floats_exact(std::string_view text, std::span<float> out, const TextSource& src) {
  Tokens tok(text);
  size_t n = 0;
  for (auto t = tok.next(); !t.empty(); t = tok.next()) {
    if (n < out.size()) out[n] = float_or_fail(t, src, tok);
    ++n;
  }
  if (n != out.size()) {
    const auto plural = [](size_t k) { return std::to_string(k) + (k == 1 ? " number" : " numbers"); };
    src.fail("expected " + plural(out.size()) + ", got " + std::to_string(n) +
             (n ? " (" + quote(trim(text)) + ")" : ""));
  }
}

Vec2f parse_vec2(std::string_view text, const TextSource& src) {
  float v[2];
  parse_floats_exact(text, v, src);
  return {v[0], v[1]};
}

Vec3f parse_vec3(std::string_view text, const TextSource& src) {
  float v[3];
  parse_floats_exact(text, v, src);
  return {v[0], v[1], v[2]};
}

Rgb parse_rgb(std::string_view text, const TextSource& src) {
  float v[3];
  parse_floats_exact(text, v, src);
  return {v[0], v[1], v[2]};
}

namespace {
thread_local FileReadObserver* t_file_read_observer = nullptr;
}  // namespace

FileReadObserver::FileReadObserver(Callback callback) : callback_(std::move(callback)), outer_(t_file_read_observer) {
  t_file_read_observer = this;
}

FileReadObserver::~FileReadObserver() { t_file_read_observer = outer_; }

std::string read_file_bytes(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path, "", "cannot read file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "", std::string("cannot open file: ") + std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw Error(path, "", "cannot read file (is it a directory?)");
  in.seekg(0, std::ios::beg);
  std::string data(static_cast<size_t>(size), '\0');
  if (size > 0 && !in.read(data.data(), size)) throw Error(path, "", "cannot read file");
  if (t_file_read_observer) t_file_read_observer->callback_(path, data);
  return data;
}

}  // namespace kiln
