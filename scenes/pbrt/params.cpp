#include "scenes/pbrt/params.h"

#include <algorithm>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "scenes/parse_util.h"

namespace kiln {
namespace {

struct TypeName {
  std::string_view name;
  PbrtType type;
};
// pbrt-v4's spellings, then the pbrt-v3 ones it still reads.
constexpr TypeName kTypeNames[] = {
    {"integer", PbrtType::Integer},   {"float", PbrtType::Float},         {"point2", PbrtType::Point2},
    {"vector2", PbrtType::Vector2},   {"point3", PbrtType::Point3},       {"vector3", PbrtType::Vector3},
    {"normal", PbrtType::Normal},     {"normal3", PbrtType::Normal},      {"rgb", PbrtType::Rgb},
    {"spectrum", PbrtType::Spectrum}, {"blackbody", PbrtType::Blackbody}, {"bool", PbrtType::Bool},
    {"string", PbrtType::String},     {"texture", PbrtType::Texture},     {"point", PbrtType::Point3},
    {"vector", PbrtType::Vector3},    {"color", PbrtType::Rgb},
};

std::optional<PbrtType> type_from_name(std::string_view s) {
  for (const TypeName& t : kTypeNames)
    if (t.name == s) return t.type;
  return std::nullopt;
}

// Values per element of an array type (its count must be a multiple of this).
size_t arity(PbrtType t) {
  switch (t) {
    case PbrtType::Point2:
    case PbrtType::Vector2: return 2;
    case PbrtType::Point3:
    case PbrtType::Vector3:
    case PbrtType::Normal:
    case PbrtType::Rgb: return 3;
    default: return 1;
  }
}

bool is_numeric(PbrtType t) {
  return t != PbrtType::Bool && t != PbrtType::String && t != PbrtType::Texture && t != PbrtType::Integer &&
         t != PbrtType::Spectrum;
}

// "0 1 2" or "400 0.5 500 0.6"; '#' starts a comment to the end of the line.
std::vector<float> read_spectrum_file(const std::string& path, const PbrtParams& ps, int line) {
  std::string text;
  try {
    text = read_file_bytes(path);
  } catch (const Error& e) {
    ps.fail(line, std::string("cannot read the spectrum file: ") + e.what());
  }
  std::vector<float> out;
  std::string_view rest(text);
  while (!rest.empty()) {
    const size_t eol = std::min(rest.find('\n'), rest.size());
    std::string_view l = rest.substr(0, eol);
    rest.remove_prefix(std::min(eol + 1, rest.size()));
    l = l.substr(0, std::min(l.find('#'), l.size()));
    for (std::string_view tok : split_whitespace(l)) {
      const auto v = to_float(tok);
      if (!v) ps.fail(line, "spectrum file " + path + ": '" + std::string(tok.substr(0, 40)) + "' is not a number");
      out.push_back(*v);
    }
  }
  return out;
}

}  // namespace

// Built piecewise: GCC 12 reports a false -Wrestrict on "\"" + s.
std::string in_quotes(std::string_view s) {
  std::string r;
  r.reserve(s.size() + 2);
  r += '"';
  r += s;
  r += '"';
  return r;
}


const char* pbrt_type_name(PbrtType t) {
  switch (t) {
    case PbrtType::Integer: return "integer";
    case PbrtType::Float: return "float";
    case PbrtType::Point2: return "point2";
    case PbrtType::Vector2: return "vector2";
    case PbrtType::Point3: return "point3";
    case PbrtType::Vector3: return "vector3";
    case PbrtType::Normal: return "normal";
    case PbrtType::Rgb: return "rgb";
    case PbrtType::Spectrum: return "spectrum";
    case PbrtType::Blackbody: return "blackbody";
    case PbrtType::Bool: return "bool";
    case PbrtType::String: return "string";
    case PbrtType::Texture: return "texture";
  }
  return "?";
}

std::string PbrtParams::location(int line) const {
  std::string s = "line " + std::to_string(line);
  if (!context_.empty()) s += " (" + context_ + ")";
  return s;
}

void PbrtParams::fail(int line, const std::string& message) const { throw Error(file_, location(line), message); }

void PbrtParams::parse(PbrtCursor& cursor) {
  while (true) {
    const auto decl_tok = cursor.peek();
    if (!decl_tok || decl_tok->kind != PbrtTokenKind::String) return;
    cursor.next();
    const int line = decl_tok->line;
    const std::string decl = pbrt_unescape(*decl_tok, file_);
    const auto words = split_whitespace(decl);
    if (words.size() != 2)
      fail(line, "expected a parameter declaration \"type name\", got \"" + decl.substr(0, 60) + "\"");
    const auto type = type_from_name(words[0]);
    if (!type)
      fail(line, "unknown parameter type \"" + std::string(words[0]) + "\" in \"" + decl.substr(0, 60) +
                     "\" (integer, float, point2, vector2, point3, vector3, normal, rgb, spectrum, blackbody, bool, "
                     "string, texture)");
    PbrtParam p;
    p.type = *type;
    p.name = std::string(words[1]);
    p.line = line;
    const std::string what = "parameter " + in_quotes(decl);

    auto add_value = [&](const PbrtToken& v) {
      const bool is_string = v.kind == PbrtTokenKind::String;
      switch (p.type) {
        case PbrtType::Integer: {
          const auto i = is_string ? std::nullopt : to_int64(v.text);
          if (!i) fail(v.line, what + ": expected an integer, got " + pbrt_describe(v));
          p.ints.push_back(*i);
          return;
        }
        case PbrtType::Bool: {
          const auto b = to_bool(v.text);
          if (!b || v.text != (*b ? "true" : "false"))
            fail(v.line, what + ": expected true or false, got " + pbrt_describe(v));
          p.bools.push_back(*b ? 1 : 0);
          return;
        }
        case PbrtType::String:
        case PbrtType::Texture:
          if (!is_string) fail(v.line, what + ": expected a quoted string, got " + pbrt_describe(v));
          p.strings.push_back(pbrt_unescape(v, file_));
          return;
        case PbrtType::Spectrum:
          if (is_string) {
            if (!p.floats.empty()) fail(v.line, what + ": mixes numbers and a name");
            p.strings.push_back(pbrt_unescape(v, file_));
            return;
          }
          if (!p.strings.empty()) fail(v.line, what + ": mixes a name and numbers");
          break;
        default: break;
      }
      const auto f = is_string ? std::nullopt : to_float(v.text);
      if (!f) fail(v.line, what + ": expected a finite number, got " + pbrt_describe(v));
      p.floats.push_back(*f);
    };

    const auto v = cursor.next();
    if (!v) fail(line, what + " has no value (the file ends)");
    if (v->kind == PbrtTokenKind::OpenBracket) {
      while (true) {
        const auto x = cursor.next();
        if (!x) fail(v->line, what + ": the file ends before the closing ']'");
        if (x->kind == PbrtTokenKind::CloseBracket) break;
        if (x->kind == PbrtTokenKind::OpenBracket) fail(x->line, what + ": '[' inside a value list");
        add_value(*x);
      }
    } else if (v->kind == PbrtTokenKind::CloseBracket) {
      fail(v->line, what + ": ']' without '['");
    } else {
      add_value(*v);
    }
    if (is_numeric(p.type) && p.floats.size() % arity(p.type) != 0)
      fail(line, what + " has " + std::to_string(p.floats.size()) + " values, not a multiple of " +
                     std::to_string(arity(p.type)));
    if (p.type == PbrtType::Spectrum && p.strings.size() > 1)
      fail(line, what + ": expected one spectrum name, got " + std::to_string(p.strings.size()));
    add(std::move(p));
  }
}

void PbrtParams::add(PbrtParam p) {
  for (PbrtParam& q : params_)
    if (q.name == p.name) {
      remarks_.push_back({p.line, "parameter " + in_quotes(p.name) + " is given twice (first on line " +
                                      std::to_string(q.line) + "); the last value is used, as pbrt does"});
      q = std::move(p);
      return;
    }
  params_.push_back(std::move(p));
}

bool PbrtParams::has(std::string_view name) const {
  for (const PbrtParam& p : params_)
    if (p.name == name) return true;
  return defaults_ && defaults_->has(name);
}

const PbrtParam* PbrtParams::find(std::string_view name, std::initializer_list<PbrtType> accepted,
                                  const char* expected) const {
  for (const PbrtParam& p : params_) {
    if (p.name != name) continue;
    if (std::find(accepted.begin(), accepted.end(), p.type) == accepted.end())
      fail(p.line, "parameter " + in_quotes(name) + " is declared \"" + pbrt_type_name(p.type) + "\"; " + context_ +
                       " expects " + expected);
    p.used = true;
    return &p;
  }
  return defaults_ ? defaults_->find(name, accepted, expected) : nullptr;
}

const PbrtParam* PbrtParams::find_one(std::string_view name, std::initializer_list<PbrtType> accepted,
                                      const char* expected) const {
  const PbrtParam* p = find(name, accepted, expected);
  if (p && p->count() != 1)
    fail(p->line, "parameter " + in_quotes(name) + " takes one value, got " + std::to_string(p->count()));
  return p;
}

std::optional<float> PbrtParams::find_float(std::string_view name) const {
  const PbrtParam* p = find_one(name, {PbrtType::Float}, "float");
  return p ? std::optional<float>(p->floats[0]) : std::nullopt;
}

std::optional<int> PbrtParams::find_int(std::string_view name) const {
  const PbrtParam* p = find_one(name, {PbrtType::Integer}, "integer");
  if (!p) return std::nullopt;
  const int64_t v = p->ints[0];
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    fail(p->line, "parameter " + in_quotes(name) + ": " + std::to_string(v) + " is out of range");
  return int(v);
}

bool PbrtParams::get_bool(std::string_view name, bool def) const {
  const PbrtParam* p = find_one(name, {PbrtType::Bool}, "bool");
  return p ? p->bools[0] != 0 : def;
}

std::optional<std::string> PbrtParams::find_string(std::string_view name) const {
  const PbrtParam* p = find_one(name, {PbrtType::String}, "string");
  return p ? std::optional<std::string>(p->strings[0]) : std::nullopt;
}

std::optional<Vec3f> PbrtParams::find_triple(std::string_view name, PbrtType type, const char* one) const {
  const PbrtParam* p = find(name, {type}, pbrt_type_name(type));
  if (!p) return std::nullopt;
  if (p->floats.size() != 3)
    fail(p->line, "parameter " + in_quotes(name) + " takes one " + one + " (3 values), got " +
                      std::to_string(p->count()));
  return Vec3f(p->floats[0], p->floats[1], p->floats[2]);
}

std::optional<Vec3f> PbrtParams::find_point3(std::string_view name) const {
  return find_triple(name, PbrtType::Point3, "point");
}

std::optional<Vec3f> PbrtParams::find_vector3(std::string_view name) const {
  return find_triple(name, PbrtType::Vector3, "vector");
}

std::vector<float> PbrtParams::get_floats(std::string_view name) const {
  const PbrtParam* p = find(name, {PbrtType::Float}, "float");
  return p ? p->floats : std::vector<float>{};
}

std::vector<std::string> PbrtParams::get_strings(std::string_view name) const {
  const PbrtParam* p = find(name, {PbrtType::String}, "string");
  return p ? p->strings : std::vector<std::string>{};
}

std::vector<int64_t> PbrtParams::get_ints(std::string_view name) const {
  const PbrtParam* p = find(name, {PbrtType::Integer}, "integer");
  return p ? p->ints : std::vector<int64_t>{};
}

std::vector<float> PbrtParams::numbers(std::string_view name, PbrtType type, size_t) const {
  const PbrtParam* p = find(name, {type}, pbrt_type_name(type));
  return p ? p->floats : std::vector<float>{};
}

std::vector<Vec3f> PbrtParams::get_point3s(std::string_view name) const {
  const std::vector<float> f = numbers(name, PbrtType::Point3, 3);
  std::vector<Vec3f> out(f.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  return out;
}

std::vector<Rgb> PbrtParams::get_rgbs(std::string_view name) const {
  const std::vector<float> f = numbers(name, PbrtType::Rgb, 3);
  std::vector<Rgb> out(f.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  return out;
}

std::vector<Vec3f> PbrtParams::get_normals(std::string_view name) const {
  const std::vector<float> f = numbers(name, PbrtType::Normal, 3);
  std::vector<Vec3f> out(f.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  return out;
}

std::vector<Vec2f> PbrtParams::get_point2s(std::string_view name) const {
  const PbrtParam* p = find(name, {PbrtType::Point2, PbrtType::Float}, "point2");
  if (!p) return {};
  if (p->floats.size() % 2 != 0)
    fail(p->line,
         "parameter " + in_quotes(name) + " has " + std::to_string(p->floats.size()) + " values, not a multiple of 2");
  std::vector<Vec2f> out(p->floats.size() / 2);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {p->floats[2 * i], p->floats[2 * i + 1]};
  return out;
}

std::optional<std::string> PbrtParams::find_texture(std::string_view name) const {
  for (const PbrtParam& p : params_)
    if (p.name == name) {
      if (p.type != PbrtType::Texture) return std::nullopt;
      if (p.strings.size() != 1) fail(p.line, "parameter " + in_quotes(name) + " names one texture");
      p.used = true;
      return p.strings[0];
    }
  return defaults_ ? defaults_->find_texture(name) : std::nullopt;
}

std::optional<Rgb> PbrtParams::find_spectrum(std::string_view name, SpectrumUse use) const {
  const PbrtParam* p = find(name, {PbrtType::Rgb, PbrtType::Spectrum, PbrtType::Blackbody, PbrtType::Texture},
                            "rgb, spectrum or blackbody");
  if (!p || p->type == PbrtType::Texture) return std::nullopt;
  if (p->type != PbrtType::Rgb) return spectrum_rgb(*piecewise_spectrum(*p), use);
  const std::string what = "parameter " + in_quotes(name);
  if (p->floats.size() != 3) fail(p->line, what + " takes 3 values, got " + std::to_string(p->count()));
  const Rgb c(p->floats[0], p->floats[1], p->floats[2]);
  if (c.has_negative()) fail(p->line, what + ": RGB components must not be negative");
  if (use == SpectrumUse::Albedo && c.max_component() > 1.0f)
    fail(p->line, what + ": a reflectance has RGB components at most 1");
  return c;
}

std::optional<PiecewiseSpectrum> PbrtParams::find_piecewise_spectrum(std::string_view name) const {
  const PbrtParam* p = find(name, {PbrtType::Rgb, PbrtType::Spectrum, PbrtType::Blackbody, PbrtType::Texture},
                            "rgb, spectrum or blackbody");
  if (!p || p->type == PbrtType::Texture || p->type == PbrtType::Rgb) return std::nullopt;
  return piecewise_spectrum(*p);
}

// A blackbody temperature, a named spectrum, a spectrum file or inline (wavelength, value) pairs.
std::optional<PiecewiseSpectrum> PbrtParams::piecewise_spectrum(const PbrtParam& p) const {
  const std::string what = "parameter " + in_quotes(p.name);
  if (p.type == PbrtType::Blackbody) {
    if (p.floats.size() != 1) fail(p.line, what + " takes one temperature (kelvin), got " + std::to_string(p.count()));
    auto s = blackbody_spectrum(p.floats[0]);
    if (!s) fail(p.line, what + ": the temperature must be positive");
    return s;
  }
  std::vector<float> pairs;
  if (!p.strings.empty()) {
    if (auto named = named_spectrum(p.strings[0])) return named;
    pairs = read_spectrum_file(spectrum_file(p), *this, p.line);
  } else {
    pairs = p.floats;
  }
  if (pairs.size() < 2 || pairs.size() % 2 != 0)
    fail(p.line, what + ": expected (wavelength, value) pairs, got " + std::to_string(pairs.size()) + " numbers");
  PiecewiseSpectrum s;
  for (size_t i = 0; i < pairs.size(); i += 2) {
    if (!s.lambda_nm.empty() && !(pairs[i] > s.lambda_nm.back())) fail(p.line, what + ": wavelengths must increase");
    if (pairs[i + 1] < 0.0f) fail(p.line, what + ": spectrum values must not be negative");
    s.lambda_nm.push_back(pairs[i]);
    s.values.push_back(pairs[i + 1]);
  }
  return s;
}

// The file a spectrum parameter names, relative to the scene file's folder. A name that is neither a file nor a
// named spectrum is reported with the nearest known names (unless it looks like a file name: then as a missing
// file).
std::string PbrtParams::spectrum_file(const PbrtParam& p) const {
  const std::string& name = p.strings[0];
  const std::filesystem::path path = std::filesystem::path(dir_) / name;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) return path.string();
  const bool looks_like_file = name.find('/') != std::string::npos || name.find('\\') != std::string::npos ||
                               std::filesystem::path(name).has_extension();
  if (looks_like_file)
    fail(p.line, "parameter " + in_quotes(p.name) + ": cannot read the spectrum file " + in_quotes(path.string()) +
                     " (no such file)");
  std::string nearest;
  for (const std::string& n : nearest_named_spectra(name)) nearest += (nearest.empty() ? "" : ", ") + in_quotes(n);
  fail(p.line, "parameter " + in_quotes(p.name) + ": " + in_quotes(name) +
                   " is not a named spectrum (nearest: " + nearest + ") nor a spectrum file");
}

std::optional<float> PbrtParams::find_float_or_spectrum(std::string_view name, bool* was_spectrum) const {
  for (const PbrtParam& p : params_)
    if (p.name == name && p.type == PbrtType::Spectrum) {
      if (was_spectrum) *was_spectrum = true;
      return find_spectrum(name, SpectrumUse::Unbounded)->g;
    }
  if (was_spectrum) *was_spectrum = false;
  return find_float(name);
}

std::vector<std::string> PbrtParams::unused_messages() const {
  std::vector<std::string> out;
  for (const PbrtParam& p : params_)
    if (!p.used)
      out.push_back(Error::format(
          file_, location(p.line),
          "parameter \"" + std::string(pbrt_type_name(p.type)) + " " + p.name + "\" is not used by Kiln; ignored"));
  return out;
}

}  // namespace kiln
